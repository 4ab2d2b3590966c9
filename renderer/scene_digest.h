// Change detection by digests (docs/DESIGN.md §2.4): the renderer compares digests of the scene's
// parts instead of relying on edits to mark anything dirty. Each digest covers exactly the
// values that one part of the GPU state is derived from.
#pragma once

#include <cstdint>

#include "renderer/scene.h"

namespace glint {

struct SceneDigests {
  uint64_t geometry = 0;     // spheres, quads and the material names they refer to
  uint64_t materials = 0;    // material values and texture slot assignments
  uint64_t textures = 0;     // texture names, paths, and the files' sizes and times
  uint64_t environment = 0;  // environment values, file and its size and time
  uint64_t camera = 0;       // camera values
  uint64_t settings = 0;     // max_bounces, seed
  uint64_t display = 0;      // exposure, tonemap: never resets the accumulation

  // Everything that affects radiance; a change restarts the accumulation.
  uint64_t radiance() const;
};

// Hashes every field of the tables of renderer/scene_fields.h but labels (kLabel: object names),
// and the size and time of each asset file; the film is in no digest (the renderer is given its
// size with each sync).
SceneDigests digest_scene(const Scene& scene);

// FNV-1a, 64 bits: a small incremental hasher for plain values.
class Hasher {
 public:
  void bytes(const void* data, size_t size);
  void value(float v);
  void value(int v);
  void value(uint32_t v);
  void value(uint64_t v);
  void value(const glm::vec2& v);
  void value(const glm::vec3& v);
  void value(const std::string& s);  // length-prefixed, so ("ab","c") != ("a","bc")
  uint64_t result() const { return state_; }

 private:
  uint64_t state_ = 14695981039346656037ull;
};

}  // namespace glint
