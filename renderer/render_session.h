// A progressive render to a target (docs/DESIGN.md §2): passes of a growing batch of samples
// per pixel into a GpuRenderer until a sample count or a time budget is reached. `glint render`
// runs one to the end, the editor's export steps one a UI slice at a time, the soak traces its
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

// How many samples a pass traces. A pass cannot be interrupted, so a batch starts small and
// doubles while a full pass takes less than grow_below seconds (fewer passes, the same
// samples), up to max_batch; it halves when a pass takes longer than shrink_above.
struct BatchPolicy {
  int first_batch = 1;
  int max_batch = 1024;
  double grow_below = 0.25;
  double shrink_above = std::numeric_limits<double>::infinity();
};

struct RenderSessionOptions {
  RenderTarget target;
  BatchPolicy batch;
  // Every power of two (1, 2, 4, ...) and a sample target are hit exactly and reported by
  // at_checkpoint(), for a convergence log.
  bool checkpoints = false;
};

class RenderSession {
 public:
  RenderSession(GpuRenderer& renderer, RenderSessionOptions options);

  // The target is reached, or the session was cancelled.
  bool done() const;
  bool cancelled() const { return cancelled_; }
  void cancel() { cancelled_ = true; }

  // Traces passes until `slice_seconds` of wall time have gone (at least one pass), the
  // target is reached or a checkpoint is; waits for each pass (glFinish) to time it. Returns
  // the samples per pixel traced; 0 once done().
  int64_t step(double slice_seconds = 0);

  // Steps to the end, calling `after_pass` after every pass (outside the traced time: a
  // checkpoint's read-back does not count as rendering). `after_pass` may cancel.
  void run(const std::function<void(RenderSession&)>& after_pass = {});

  // Which limit ended it; none while it runs.
  StopReason stop_reason() const;
  // The estimated relMSE after the last pass, known when the target has an error (it is
  // computed after every pass then); otherwise -1.
  double estimated_relmse() const { return estimated_relmse_; }

  // The last pass ended on a checkpoint (options.checkpoints).
  bool at_checkpoint() const { return at_checkpoint_; }
  int64_t samples() const;
  double seconds() const { return seconds_; }  // wall time of the passes so far
  float progress() const;                       // 0..1 of the target
  const RenderSessionOptions& options() const { return options_; }
  // Tightens or loosens the batch policy, keeping the batch reached (the export follows the
  // UI's trace budget); the batch is clamped into the new bounds.
  void set_batch_policy(const BatchPolicy& policy);
  int batch() const { return batch_; }

 private:
  bool target_reached() const;
  void trace_pass();

  GpuRenderer& renderer_;
  RenderSessionOptions options_;
  int batch_ = 1;
  int64_t checkpoint_ = 0;  // the next one, 0 without checkpoints
  bool at_checkpoint_ = false;
  bool cancelled_ = false;
  double seconds_ = 0;
  double estimated_relmse_ = -1;
};

}  // namespace glint
