// The viewport's side of one frame (docs/DESIGN.md §2): renderer.sync(scene, size), k samples
// chosen by the frame budget, update_display(); and one slice of a running export. Every
// accumulation reset comes from sync() comparing digests: nothing here resets on its own.
#pragma once

#include <chrono>
#include <memory>

#include "editor/frame_budget.h"
#include "editor/ui.h"
#include "renderer/gpu_renderer.h"

namespace glint {

class ViewportRenderer {
 public:
  // Needs a current OpenGL 4.5 context.
  explicit ViewportRenderer(GpuRendererOptions options = {});

  // The render_viewport hook of EditorState. Leaves the default framebuffer bound with the
  // viewport set to framebuffer_size (what ImGui's renderer expects afterwards).
  void render(Document& doc, EditorState& state);
  void set_framebuffer_size(int w, int h) { fb_w_ = w; fb_h_ = h; }
  void set_max_samples(int64_t spp) { max_spp_ = spp; }  // stop tracing once reached

  GpuRenderer& renderer() { return renderer_; }
  FrameBudget& budget() { return budget_; }

 private:
  GpuRenderer renderer_;
  FrameBudget budget_;
  int fb_w_ = 0, fb_h_ = 0;
  int64_t max_spp_ = 1 << 20;
  unsigned filtered_texture_ = 0;
  std::chrono::steady_clock::time_point last_frame_{};
  std::chrono::steady_clock::time_point rate_start_{};
  int64_t rate_samples_ = 0;
  double spp_rate_ = 0;
  double last_trace_seconds_ = 0;
};

}  // namespace glint
