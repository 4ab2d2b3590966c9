#include "renderer/render_session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <epoxy/gl.h>

#include "renderer/backend_choice.h"
#include "renderer/gpu_renderer.h"
#include "renderer/stopwatch.h"

namespace glint {
namespace {

using Clock = std::chrono::steady_clock;

// The checkpoint after `samples`: the next power of two, or the sample target if that is
// nearer (0 for a time target: powers of two only).
int64_t next_checkpoint(int64_t samples, int64_t target) {
  int64_t p = 1;
  while (p <= samples) p *= 2;
  return target > 0 ? std::min(p, target) : p;
}

bool time_target(const RenderTarget& t) { return t.seconds > 0; }
bool error_target(const RenderTarget& t) { return t.error > 0; }
// The sample count that ends the session, 0 for none.
int64_t sample_cap(const RenderTarget& t) {
  return error_target(t) || !time_target(t) ? std::max<int64_t>(0, t.samples) : 0;
}

}  // namespace

int band_rows_for_threads(int width, int threads) {
  const int tiles_per_row = llvmpipe_tiles_across(width);
  const int tile_rows = (4 * std::max(1, threads) + tiles_per_row - 1) / tiles_per_row;
  return kLlvmpipeTileSize * tile_rows;
}

const char* stop_reason_text(StopReason reason) {
  switch (reason) {
    case StopReason::samples: return "sample count";
    case StopReason::time: return "time";
    case StopReason::error: return "error target";
    case StopReason::cancelled: return "cancelled";
    case StopReason::none: break;
  }
  return "none";
}

RenderSession::RenderSession(GpuRenderer& renderer, RenderSessionOptions options)
    : renderer_(renderer), options_(options) {
  const RenderTarget& t = options_.target;
  if (!time_target(t) && !error_target(t) && t.samples < 1)
    throw std::invalid_argument("a render session needs a sample target of at least 1 or a time target");
  if (error_target(t) && !time_target(t) && t.samples < 1)
    throw std::invalid_argument("a render session with an error target needs a sample or a time cap");
  set_batch_policy(options_.batch);
  batch_ = std::clamp(options_.batch.first_batch, 1, std::max(1, options_.batch.max_batch));
  if (options_.checkpoints)
    checkpoint_ = next_checkpoint(samples(), sample_cap(options_.target));
}

int64_t RenderSession::samples() const { return renderer_.sample_count(); }

StopReason RenderSession::stop_reason() const {
  const RenderTarget& t = options_.target;
  if (renderer_.pass_under_way()) return cancelled_ ? StopReason::cancelled : StopReason::none;
  if (error_target(t) && samples() >= kErrorTargetMinSamples && estimated_relmse_ >= 0 &&
      estimated_relmse_ <= t.error)
    return StopReason::error;
  if (sample_cap(t) > 0 && samples() >= sample_cap(t)) return StopReason::samples;
  if (time_target(t) && seconds_ >= t.seconds && samples() > 0) return StopReason::time;
  if (cancelled_) return StopReason::cancelled;
  return StopReason::none;
}

bool RenderSession::target_reached() const {
  const StopReason r = stop_reason();
  return r != StopReason::none && r != StopReason::cancelled;
}

bool RenderSession::done() const { return cancelled_ || target_reached(); }

float RenderSession::progress() const {
  if (target_reached()) return 1;
  const RenderTarget& t = options_.target;
  double p = 0;
  if (time_target(t)) p = std::max(p, seconds_ / t.seconds);
  if (sample_cap(t) > 0) p = std::max(p, traced_samples() / double(sample_cap(t)));
  // relMSE falls as 1/n: the fraction of the samples needed so far.
  if (error_target(t) && estimated_relmse_ > 0) p = std::max(p, t.error / estimated_relmse_);
  return static_cast<float>(std::clamp(p, 0.0, 1.0));
}

double RenderSession::traced_samples() const {
  double traced = double(samples());
  if (renderer_.pass_under_way() && renderer_.height() > 0)
    traced += pass_samples_ * double(renderer_.height() - renderer_.pass_rows_left()) / renderer_.height();
  return traced;
}

void RenderSession::set_batch_policy(const BatchPolicy& policy) {
  options_.batch = policy;
  batch_ = std::clamp(batch_, 1, std::max(1, policy.max_batch));
}

void RenderSession::begin_pass() {
  // The batch, capped at the sample target and the next checkpoint so that both are hit
  // exactly.
  int64_t k = batch_;
  if (sample_cap(options_.target) > 0) k = std::min(k, sample_cap(options_.target) - samples());
  // Towards an error target, relMSE falls as 1/n: a pass need not go much beyond the samples
  // that the last estimate says are missing (it would overshoot the target by the batch).
  // Before the first estimate (fewer than two samples), no further than the minimum: a batch
  // grown by the first pass's rate could otherwise overshoot the target by far.
  if (error_target(options_.target)) {
    int64_t allowed = std::max<int64_t>(1, kErrorTargetMinSamples - samples());
    if (estimated_relmse_ >= 0) {
      const double needed = double(samples()) * (estimated_relmse_ / options_.target.error - 1.0);
      allowed = std::max(allowed, static_cast<int64_t>(std::ceil(needed)));
    }
    k = std::min(k, allowed);
  }
  if (checkpoint_ > 0) k = std::min(k, checkpoint_ - samples());
  pass_samples_ = static_cast<int>(k);
  pass_seconds_ = 0;
  renderer_.begin_pass(pass_samples_);
}

double RenderSession::row_seconds(int64_t samples) const {
  return pixel_sample_seconds_ * renderer_.width() * double(samples);
}

// The whole rest of the pass untiled; tiled, as many rows as fit in `seconds_left` (at least
// one; one to measure the cost at first), rounded up to a multiple of band_rows.
void RenderSession::trace_band(double seconds_left) {
  int rows = renderer_.pass_rows_left();
  if (options_.tiled) {
    const double row = row_seconds(pass_samples_);
    const double fit = row > 0 ? std::floor(seconds_left / row) : 1.0;
    const double multiple = std::max(1, options_.band_rows);
    const double band = std::ceil(std::clamp(fit, 1.0, double(rows)) / multiple) * multiple;
    rows = static_cast<int>(std::min(band, double(rows)));
  }
  const auto start = Clock::now();
  const int traced = renderer_.trace_rows(rows);
  glFinish();  // the band's real time (and bands do not queue up)
  const double t = seconds_since(start);
  seconds_ += t;
  pass_seconds_ += t;
  const int64_t pixel_samples = int64_t(traced) * renderer_.width() * pass_samples_;
  step_pixel_samples_ += pixel_samples;
  if (pixel_samples > 0) pixel_sample_seconds_ = t / double(pixel_samples);
  if (!renderer_.pass_under_way()) end_pass();
}

void RenderSession::end_pass() {
  const double t = pass_seconds_;
  // Outside the timed pass: the estimate is a small read-back (renderer/error_estimate.h).
  if (error_target(options_.target)) {
    const ErrorEstimate e = renderer_.estimate_error();
    estimated_relmse_ = e.known() ? e.relmse : -1;
  }
  const BatchPolicy& p = options_.batch;
  if (pass_samples_ == batch_ && t < p.grow_below && batch_ < p.max_batch) {
    double next = 2.0 * batch_;
    if (p.grow_by_rate && t > 0) next = std::max(next, std::floor(batch_ * (p.grow_below / t)));
    batch_ = static_cast<int>(std::min(next, double(p.max_batch)));
  } else if (t > p.shrink_above && batch_ > 1) batch_ /= 2;
  at_checkpoint_ = checkpoint_ > 0 && samples() == checkpoint_;
  if (at_checkpoint_) checkpoint_ = next_checkpoint(samples(), sample_cap(options_.target));
}

int64_t RenderSession::step(double slice_seconds) {
  const int64_t before = samples();
  at_checkpoint_ = false;
  step_pixel_samples_ = 0;
  const auto start = Clock::now();
  while (!cancelled_) {
    if (!renderer_.pass_under_way()) {
      if (done()) break;
      begin_pass();
    }
    trace_band(slice_seconds - seconds_since(start));
    const double left = slice_seconds - seconds_since(start);
    if (at_checkpoint_ || left <= 0) break;
    // Tiled: no band that would not fit (the next pass's is at most the batch).
    if (options_.tiled && left < row_seconds(renderer_.pass_under_way() ? pass_samples_ : batch_)) break;
  }
  return samples() - before;
}

void RenderSession::run(const std::function<void(RenderSession&)>& after_pass) {
  while (!done()) {
    step(0);
    if (after_pass && !renderer_.pass_under_way()) after_pass(*this);
  }
}

void RenderSession::run(double slice_seconds, const std::function<void(RenderSession&)>& on_step) {
  while (!done()) {
    step(slice_seconds);
    if (on_step) on_step(*this);
  }
}

}  // namespace glint
