#include "renderer/render_session.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include <epoxy/gl.h>

#include "renderer/gpu_renderer.h"

namespace glint {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// The checkpoint after `samples`: the next power of two, or the sample target if that is
// nearer (0 for a time target: powers of two only).
int64_t next_checkpoint(int64_t samples, int64_t target) {
  int64_t p = 1;
  while (p <= samples) p *= 2;
  return target > 0 ? std::min(p, target) : p;
}

bool time_target(const RenderTarget& t) { return t.seconds > 0; }

}  // namespace

RenderSession::RenderSession(GpuRenderer& renderer, RenderSessionOptions options)
    : renderer_(renderer), options_(options) {
  if (!time_target(options_.target) && options_.target.samples < 1)
    throw std::invalid_argument("a render session needs a sample target of at least 1 or a time target");
  set_batch_policy(options_.batch);
  batch_ = std::clamp(options_.batch.first_batch, 1, std::max(1, options_.batch.max_batch));
  if (options_.checkpoints)
    checkpoint_ = next_checkpoint(samples(), time_target(options_.target) ? 0 : options_.target.samples);
}

int64_t RenderSession::samples() const { return renderer_.sample_count(); }

bool RenderSession::target_reached() const {
  return time_target(options_.target) ? seconds_ >= options_.target.seconds && samples() > 0
                                      : samples() >= options_.target.samples;
}

bool RenderSession::done() const { return cancelled_ || target_reached(); }

float RenderSession::progress() const {
  if (target_reached()) return 1;
  const double p = time_target(options_.target) ? seconds_ / options_.target.seconds
                                                : double(samples()) / double(options_.target.samples);
  return static_cast<float>(std::clamp(p, 0.0, 1.0));
}

void RenderSession::set_batch_policy(const BatchPolicy& policy) {
  options_.batch = policy;
  batch_ = std::clamp(batch_, 1, std::max(1, policy.max_batch));
}

void RenderSession::trace_pass() {
  // The batch, capped at the sample target and the next checkpoint so that both are hit
  // exactly.
  int64_t k = batch_;
  if (!time_target(options_.target)) k = std::min(k, options_.target.samples - samples());
  if (checkpoint_ > 0) k = std::min(k, checkpoint_ - samples());
  const auto start = Clock::now();
  renderer_.trace(static_cast<int>(k));
  glFinish();  // the pass's real time (and passes do not queue up)
  const double t = seconds_since(start);
  seconds_ += t;
  const BatchPolicy& p = options_.batch;
  if (k == batch_ && t < p.grow_below && batch_ < p.max_batch) batch_ = std::min(batch_ * 2, p.max_batch);
  else if (t > p.shrink_above && batch_ > 1) batch_ /= 2;
  at_checkpoint_ = checkpoint_ > 0 && samples() == checkpoint_;
  if (at_checkpoint_)
    checkpoint_ = next_checkpoint(samples(), time_target(options_.target) ? 0 : options_.target.samples);
}

int64_t RenderSession::step(double slice_seconds) {
  const int64_t before = samples();
  at_checkpoint_ = false;
  const auto start = Clock::now();
  do {
    if (done()) break;
    trace_pass();
  } while (!at_checkpoint_ && seconds_since(start) < slice_seconds);
  return samples() - before;
}

void RenderSession::run(const std::function<void(RenderSession&)>& after_pass) {
  while (!done()) {
    step(0);
    if (after_pass) after_pass(*this);
  }
}

}  // namespace glint
