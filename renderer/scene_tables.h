// The scene's tables as the trace shader reads them (shaders/trace_common.glsl): integer buffer
// textures of spheres, quads, materials, texture layer records, lights, environment-sampling
// tables, BVH nodes and BVH primitives, table k on texture unit kFirstUnit + k; and the first
// shapes again as the uniform block of an unrolled loop (renderer/loop_shapes.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "renderer/gpu_scene.h"

namespace glint {

enum class SceneTable { spheres, quads, materials, layers, lights, environment, bvh_nodes, bvh_primitives };

// The texels a table of `data` needs (one per 16 bytes, or one per int or float).
template <typename T>
int64_t table_texels(const std::vector<T>& data) {
  static_assert(sizeof(T) % 16 == 0 || sizeof(T) == 4, "an RGBA32I or R32I texel layout");
  return int64_t(data.size()) * (sizeof(T) % 16 == 0 ? int64_t(sizeof(T) / 16) : 1);
}

// Throws std::runtime_error naming `what` (its `count` elements, `texels` texels) and `limit`
// when the texels are more than a table holds.
void check_table_texels(const std::string& what, size_t count, int64_t texels, int64_t limit);

class SceneTables {
 public:
  static constexpr int kCount = 8;
  static constexpr GLuint kFirstUnit = 7;

  // Every table empty (each is bound for every pass, so it never lacks storage). `max_texels`:
  // the texels a table may hold, 0 for the driver's GL_MAX_TEXTURE_BUFFER_SIZE (at most
  // INT_MAX either way).
  explicit SceneTables(int64_t max_texels);
  ~SceneTables();
  SceneTables(const SceneTables&) = delete;
  SceneTables& operator=(const SceneTables&) = delete;

  int64_t max_texels() const { return max_texels_; }
  // Throws std::runtime_error if `data`, called `what` in the message, is more than a table holds.
  template <typename T>
  void check_size(const std::string& what, const std::vector<T>& data) const {
    check_table_texels(what, data.size(), table_texels(data), max_texels_);
  }
  // Replaces the contents of `table` (see upload_bytes for the storage's size).
  template <typename T>
  void upload(SceneTable table, const std::vector<T>& data) {
    upload_bytes(table, data.data(), int64_t(data.size()) * int64_t(sizeof(T)), sizeof(T) % 16 == 0);
  }
  void upload_loop_shapes(const std::vector<GpuSphere>& spheres, const std::vector<GpuQuad>& quads);

  // Binds the tables to their texture units and the loop shapes to their uniform block.
  void bind() const;
  std::vector<GLuint> textures() const { return {textures_, textures_ + kCount}; }
  GLuint loop_shapes_buffer() const { return loop_shapes_buffer_; }

 private:
  void upload_bytes(SceneTable table, const void* data, int64_t bytes, bool rgba);

  int64_t max_texels_ = 0;
  GLuint textures_[kCount] = {};
  GLuint buffers_[kCount] = {};  // their storage
  GLuint loop_shapes_buffer_ = 0;
};

// What upload_geometry put in the tables.
struct GeometryCounts {
  int spheres = 0;
  int quads = 0;
  int lights = 0;
};

// Uploads the packed scene's spheres, quads, materials, lights and loop shapes, all checked
// before any is replaced: a refused scene (std::runtime_error) leaves the previous one in place.
GeometryCounts upload_geometry(SceneTables& tables, const PackedScene& packed);

}  // namespace glint
