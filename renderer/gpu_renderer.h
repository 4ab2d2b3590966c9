// The progressive GPU path tracer (DESIGN.md §2). Runs in any current OpenGL 4.5 core context.
//
// Per frame: sync(scene) compares digests and uploads only what changed, restarting the
// accumulation when radiance inputs changed; trace(k) adds k samples per pixel into ping-pong
// RGBA32F buffers; update_display() re-runs the tonemap pass when its inputs changed.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include <epoxy/gl.h>

#include "renderer/gpu_scene.h"
#include "renderer/image.h"
#include "renderer/render_options.h"
#include "renderer/scene.h"
#include "renderer/scene_digest.h"

namespace glint {

class GlProgram;

struct SyncResult {
  bool accumulation_reset = false;  // radiance inputs or the resolution changed
  bool display_changed = false;     // exposure or tonemap changed (no reset on its own)
};

class GpuRenderer {
 public:
  GpuRenderer();  // compiles the shaders; throws std::runtime_error with the driver's log
  ~GpuRenderer();
  GpuRenderer(const GpuRenderer&) = delete;
  GpuRenderer& operator=(const GpuRenderer&) = delete;

  // Brings the GPU state up to date with a validated scene rendered at width x height.
  // Throws ImageError if a texture cannot be loaded; the previous state is then kept.
  SyncResult sync(const Scene& scene, int width, int height);

  // Takes effect at the next sync, which then restarts the accumulation if they changed.
  void set_options(const RenderOptions& options) { options_ = options; }
  const RenderOptions& options() const { return options_; }

  // Adds `samples` samples to every pixel in one pass.
  void trace(int samples);

  // Re-runs the tonemap pass if the accumulation or the display settings changed since the
  // last run. Never touches the accumulation.
  void update_display();

  int64_t sample_count() const { return samples_; }
  // GPU time of the trace passes since the accumulation was last reset, from GL_TIMESTAMP
  // queries around each pass. Waits for passes still in flight; trace() itself never waits.
  double trace_gpu_seconds();
  int width() const { return width_; }
  int height() const { return height_; }
  GLuint display_texture() const { return display_texture_; }

  // Mean linear radiance per pixel (rgb) and the count of discarded non-finite samples (a).
  Image read_accumulation() const;
  // The tonemapped display image in [0,1] (calls update_display first).
  Image read_display();

 private:
  void resize(int width, int height);
  void upload_geometry(const PackedScene& packed);
  void upload_textures(const Scene& scene, const std::vector<TextureLayer>& layers);
  void upload_environment(const Scene& scene);
  void set_frame_uniforms(const Scene& scene);
  void collect_trace_timers(bool wait);

  std::unique_ptr<GlProgram> trace_program_;
  std::unique_ptr<GlProgram> tonemap_program_;
  GLuint vao_ = 0;
  GLuint accumulation_[2] = {0, 0};
  GLuint accumulation_fbo_[2] = {0, 0};
  GLuint display_texture_ = 0;
  GLuint display_fbo_ = 0;
  GLuint buffers_[5] = {0, 0, 0, 0, 0};  // spheres, quads, materials, layer sizes, lights
  GLuint texture_array_ = 0;
  GLuint environment_texture_ = 0;

  int current_ = 0;  // accumulation_[current_] holds the latest result
  int width_ = 0;
  int height_ = 0;
  int64_t samples_ = 0;
  bool display_stale_ = true;
  bool first_sync_ = true;
  SceneDigests digests_;
  RenderOptions options_;
  glm::dvec3 origin_{0};  // render_origin of the packed scene
  RenderOptions synced_options_;
  int light_count_ = 0;
  std::vector<TextureLayer> layers_;  // what texture_array_ holds, layer by layer
  std::vector<GLuint> trace_timers_;  // timestamp pairs of trace passes not yet read, oldest first
  double trace_gpu_seconds_ = 0;
};

// Writes the render as a final image, chosen by the file's extension: .png is the tonemapped
// display image; .hdr and .exr hold the linear radiance with alpha 1. Throws ImageError.
void save_render(GpuRenderer& renderer, const std::filesystem::path& file);

}  // namespace glint
