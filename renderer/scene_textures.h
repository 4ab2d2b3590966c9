// The scene's images on the GPU: the texels of its textures and its environment map, with the
// tables that go with them (texture layer records, environment-sampling tables) in the scene
// tables (renderer/scene_tables.h).
//
// Texture storage. The shader filters by hand (lib/mapping.glsl), so each texture is a row-major
// run of texels in one long sequence, stored row after row in a 2-D texture of kTexelRowWidth
// texels a row (2-D, not a buffer texture: that may hold as few as 2^16 texels, 2^27 on
// llvmpipe, and 768 MiB of 8-bit texels are more than 2^27). Memory is the sum of the real
// sizes (a texture array takes the largest width times the largest height for every layer,
// 8 GiB for a 16384x1 and a 1x16384 texture), the count is bounded only by the layer records'
// table (an array by GL_MAX_ARRAY_TEXTURE_LAYERS, 2048 on llvmpipe), and 8-bit textures keep 4
// bytes a texel. There are two sequences because a texture has one format (RGBA8, RGBA32F). An
// atlas would need packing and would still cap a side; arrays per size class would need a
// sampler per class.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "renderer/gpu_scene.h"
#include "renderer/image.h"
#include "renderer/scene.h"

namespace glint {

class SceneTables;

// Texels per row of the colour textures that hold the textures' texels (TEXEL_ROW_SHIFT in
// shaders/trace_common.glsl).
constexpr int kTexelRowWidth = 16384;

// Where the layers' texels go in the two sequences ([0] 8-bit, [1] float), each file's texels
// once, also when several layers read them (colour and roughness).
struct TexelPlan {
  struct Run {
    const TextureImage* image;
    int64_t first;  // its first texel in its sequence
  };
  std::vector<Run> runs[2];
  int64_t texels[2] = {0, 0};
  std::vector<glm::ivec4> records;  // per layer: width, height, first texel, gpu::TEXELS_* format
};

// Plans layer i of `layers` from images[i], read from files[i]. Throws ImageError naming the
// layer's JSON path (textures[N].path) and file when a sequence would need more than `limit`
// texels.
TexelPlan plan_texels(const std::vector<TextureLayer>& layers,
                      const std::vector<std::shared_ptr<const TextureImage>>& images,
                      const std::vector<std::filesystem::path>& files, int64_t limit);

class SceneTextures {
 public:
  // `max_texels`: the texels the textures of one kind may hold together, 0 for the driver's
  // limit (kTexelRowWidth x GL_MAX_TEXTURE_SIZE).
  explicit SceneTextures(int64_t max_texels);
  ~SceneTextures();
  SceneTextures(const SceneTextures&) = delete;
  SceneTextures& operator=(const SceneTextures&) = delete;

  // Loads the textures of `layers` (through renderer/texture_cache.h) and replaces the texels
  // and the layer records. Throws ImageError naming the JSON path, the file and the limit when
  // one cannot be loaded or held; the previous textures are then kept.
  void upload_textures(const Scene& scene, const std::vector<TextureLayer>& layers, SceneTables& tables);
  // What the texels hold, layer by layer.
  const std::vector<TextureLayer>& layers() const { return layers_; }

  // Loads the environment map (white 1x1 without one) and replaces it and its sampling tables;
  // returns the tables' size (u_env_distribution_size). Throws ImageError naming
  // environment.texture and the file; the previous map is then kept.
  glm::ivec2 upload_environment(const Scene& scene, SceneTables& tables);

  GLuint texels_8bit() const { return texel_textures_[0]; }
  GLuint texels_float() const { return texel_textures_[1]; }
  GLuint environment() const { return environment_texture_; }
  // environment_peak_share of the map (0 without one), for manifold next-event estimation.
  double environment_peak_share() const { return environment_peak_share_; }

 private:
  int64_t max_texels_ = 0;
  GLuint texel_textures_[2] = {0, 0};  // RGBA8, RGBA32F
  GLuint environment_texture_ = 0;
  double environment_peak_share_ = 0;
  std::vector<TextureLayer> layers_;
};

}  // namespace glint
