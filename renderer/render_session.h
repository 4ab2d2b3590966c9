// A progressive render to a target (docs/DESIGN.md §5.1): passes of a growing batch of samples
// per pixel into a GpuRenderer until a sample count or a time budget is reached. `glint render`
// runs one to the end, the editor's export steps one a UI slice at a time (its passes traced in
// bands of rows, so that a slice stays short even when a pass does not), the soak traces its
// paired samples with one. Needs a current OpenGL 4.5 context; the renderer is synced first.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>

namespace glint {

class GpuRenderer;

// What ends the render: exactly `samples` samples per pixel or, when seconds > 0, `seconds` of
// tracing (at least one sample). With an error target (error > 0): the estimated relMSE of the
// image (GpuRenderer::estimate_error) at most `error`, or `samples` (when > 0) or `seconds`
// (when > 0) as caps, whichever comes first.
// An error target is never met before kErrorTargetMinSamples samples per pixel: with fewer,
// the variance of a pixel is estimated from too few samples to be trusted (a pixel whose rare
// bright paths have not been found yet looks converged).
inline constexpr int64_t kErrorTargetMinSamples = 16;
struct RenderTarget {
  int64_t samples = 64;
  double seconds = 0;
  double error = 0;
};

// Which limit ended a session (RenderSession::stop_reason).
enum class StopReason { none, samples, time, error, cancelled };
const char* stop_reason_text(StopReason reason);  // "sample count", "time", "error target", ...

// How many samples a pass traces. A batch starts small and doubles while a full pass takes
// less than grow_below seconds (fewer passes, the same samples), up to max_batch; it halves
// when a pass takes longer than shrink_above. With grow_by_rate it grows instead to the batch
// that the last pass's rate says takes grow_below seconds (at least double): the first pass
// measures, the next ones are full. Few large passes are faster than many small ones: a
// pass's draws trace up to the loop budget's samples per pixel, and with path regeneration a
// lane whose path ends starts the pixel's next sample, so a one-sample draw leaves the lanes
// of short paths idle (bench/reports/THROUGHPUT.md).
struct BatchPolicy {
  int first_batch = 1;
  int max_batch = 1024;
  double grow_below = 0.25;
  double shrink_above = std::numeric_limits<double>::infinity();
  bool grow_by_rate = false;
};

struct RenderSessionOptions {
  RenderTarget target;
  BatchPolicy batch;
  // Every power of two (1, 2, 4, ...) and a sample target are hit exactly and reported by
  // at_checkpoint(), for a convergence log.
  bool checkpoints = false;
  // Trace each pass in bands of rows (GpuRenderer::begin_pass, trace_rows), each sized from the
  // measured time per pixel-sample to what is left of step()'s slice, so that a step takes
  // about its slice even when a whole pass takes far longer (the editor's export, and `glint
  // render` without --time, so that large images get passes of many samples and a progress
  // bar that still moves). The image is the same as untiled for the same passes; the targets
  // are checked between passes only.
  bool tiled = false;
  // A band's rows are a multiple of this (the pass's last band excepted): llvmpipe shades in
  // tiles of 64x64 pixels, one tile per thread at a time, and a band that covers a few tiles
  // partly leaves threads idle (band_rows_for_threads).
  int band_rows = 1;
};

// Bands of whole 64-row tile rows holding at least four tiles per CPU thread (llvmpipe runs a
// thread per CPU), so that a band keeps every thread busy to its end: for an image `width`
// pixels wide on a machine of `threads` threads.
int band_rows_for_threads(int width, int threads);

class RenderSession {
 public:
  RenderSession(GpuRenderer& renderer, RenderSessionOptions options);

  // The target is reached, or the session was cancelled.
  bool done() const;
  bool cancelled() const { return cancelled_; }
  void cancel() { cancelled_ = true; }

  // Traces passes until `slice_seconds` of wall time have gone (at least one pass), the
  // target is reached or a checkpoint is; waits for each pass (glFinish) to time it. Tiled: a
  // band of rows at least instead of a pass, and no further band once the time left is less
  // than a row takes. Returns the samples per pixel of the passes that ended; 0 once done().
  int64_t step(double slice_seconds = 0);
  // Pixel-samples (rows x width x the pass's samples per pixel) the last step() traced.
  int64_t step_pixel_samples() const { return step_pixel_samples_; }

  // Steps to the end, calling `after_pass` after every pass (outside the traced time: a
  // checkpoint's read-back does not count as rendering). `after_pass` may cancel.
  void run(const std::function<void(RenderSession&)>& after_pass = {});
  // Steps of `slice_seconds` each (step()) to the end, calling `on_step` after every step, also
  // one that ended inside a pass (a tiled band): to show progress while a long pass runs, and
  // to read a checkpoint back (at_checkpoint()), outside the traced time. `on_step` may cancel.
  void run(double slice_seconds, const std::function<void(RenderSession&)>& on_step);

  // Which limit ended it; none while it runs.
  StopReason stop_reason() const;
  // The estimated relMSE after the last pass, known when the target has an error (it is
  // computed after every pass then); otherwise -1.
  double estimated_relmse() const { return estimated_relmse_; }

  // The last pass ended on a checkpoint (options.checkpoints).
  bool at_checkpoint() const { return at_checkpoint_; }
  int64_t samples() const;
  // samples() and the part of the pass under way whose rows are traced (tiled), per pixel.
  double traced_samples() const;
  double seconds() const { return seconds_; }  // wall time of the passes so far
  float progress() const;                       // 0..1 of the target
  const RenderSessionOptions& options() const { return options_; }
  // Tightens or loosens the batch policy, keeping the batch reached (the export follows the
  // UI's trace budget); the batch is clamped into the new bounds.
  void set_batch_policy(const BatchPolicy& policy);
  int batch() const { return batch_; }

 private:
  bool target_reached() const;
  void begin_pass();
  void trace_band(double seconds_left);
  void end_pass();
  double row_seconds(int64_t samples) const;  // a row's predicted time, 0 before any is measured

  GpuRenderer& renderer_;
  RenderSessionOptions options_;
  int batch_ = 1;
  int64_t checkpoint_ = 0;  // the next one, 0 without checkpoints
  bool at_checkpoint_ = false;
  bool cancelled_ = false;
  double seconds_ = 0;
  double estimated_relmse_ = -1;
  int pass_samples_ = 0;      // per pixel, of the pass under way or the last one
  double pass_seconds_ = 0;   // of the bands of the pass under way
  double pixel_sample_seconds_ = 0;  // the last band's time per pixel-sample, 0 before one
  int64_t step_pixel_samples_ = 0;
};

}  // namespace glint
