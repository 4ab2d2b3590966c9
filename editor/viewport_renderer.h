// The viewport's side of one frame (docs/DESIGN.md §2.1): renderer.sync(scene, size), k samples
// chosen by the frame budget, update_display(). Every accumulation reset comes from sync()
// comparing digests: nothing here resets on its own. Knows no UI: a ViewportRequest in, a
// ViewportFrame out.
#pragma once

#include <chrono>
#include <memory>

#include "editor/frame_budget.h"
#include "editor/held_image.h"
#include "editor/sample_rate.h"
#include "editor/viewport_denoiser.h"
#include "editor/viewport_frame.h"
#include "renderer/gpu_renderer.h"

namespace glint {

// The viewport's error estimate is refreshed this often (seconds): each refresh is a few small
// draws and a read-back of at most 32x32 sums that waits for the GPU (renderer/error_estimate.h;
// measured 16 ms on llvmpipe on this loaded 2-core machine, against 105 ms for one sample of
// projects/default.glint at the viewport's 123x69).
constexpr double kViewportEstimateSeconds = 0.25;

// The viewport stops tracing here (about a million samples per pixel: converged long before).
constexpr int64_t kViewportMaxSamples = int64_t(1) << 20;

// A pass over fewer pixels is traced whole even where it takes longer than a frame's slice:
// its time is then mostly each call's fixed cost (set-up, the wait), which bands would repeat.
constexpr int64_t kMinBandedPixels = int64_t(1) << 16;

class ViewportRenderer {
 public:
  // Needs a current OpenGL 4.5 context.
  explicit ViewportRenderer(GpuRendererOptions options = {});

  // Brings the image of `scene` up to date at the request's size and returns it. Leaves the
  // default framebuffer bound.
  ViewportFrame render(const Scene& scene, const ViewportRequest& request);

  // Seconds a running export traces per UI frame, while the viewport pauses
  // (FrameBudget::export_slice_seconds).
  double export_slice_seconds() const { return budget_.export_slice_seconds(); }
  // Seconds another renderer traced in this frame (a running export's slice): the frame budget
  // counts them as tracing, not as the UI's own time, which would shrink the next slices.
  void add_trace_seconds(double seconds) { last_trace_seconds_ += seconds; }
  // The seconds this frame spent tracing (after render()).
  double traced_seconds() const { return last_trace_seconds_; }

  GpuRenderer& renderer() { return renderer_; }
  FrameBudget& budget() { return budget_; }
  const PreviewResolution& preview() const { return preview_; }

 private:
  // The frame's trace size and whether the scene reached the renderer.
  struct Sync {
    int full_w = 1, full_h = 1;  // the viewport's framebuffer pixels
    int divisor = 1;             // traced at full / divisor
    bool synced = false;         // the scene is valid and the renderer holds it
    PreviewFrame preview;        // what the automatic level saw this frame
  };
  void record_frame_time();
  // Hands the scene (framed to the export's film) to the renderer at the level's size.
  Sync sync_scene(const Scene& scene, const ViewportRequest& request, FrameStats& stats);
  void update_estimate(bool synced, bool restarted);
  // The region, the samples of this frame and the slice they may take.
  void trace_for_request(const ViewportRequest& request, const Sync& sync,
                         const std::optional<PixelRect>& region, bool restarted);
  // The texture the viewport shows: the display, the denoised one or the held coarser level.
  unsigned shown_texture(const Scene& scene, const ViewportRequest& request, FrameStats& stats);
  // Traces `samples` per pixel, or the next band of a pass too long for `slice_seconds`.
  void trace_slice(int samples, double slice_seconds, int64_t full_pixels);

  GpuRenderer renderer_;
  FrameBudget budget_;
  PreviewResolution preview_;  // the automatic mode's level
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  unsigned filtered_texture_ = 0;
  std::string gl_renderer_;
  double ms_per_frame_ = 0;  // smoothed
  std::chrono::steady_clock::time_point last_frame_{};
  SampleRate rate_;
  double last_trace_seconds_ = 0;
  double pass_seconds_ = 0;  // the bands of the pass under way so far
  std::chrono::steady_clock::time_point last_estimate_{};
  double estimated_relmse_ = -1;
  std::unique_ptr<ViewportDenoiser> denoiser_;  // from the first request to denoise
  unsigned last_denoised_ = 0;
  HeldImage held_;  // the coarser level's image while a finer one traces its first pass
};

}  // namespace glint
