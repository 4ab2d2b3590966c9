// How much to trace per UI frame: samples per pixel (k) and a viewport resolution divisor.
//
// A trace pass cannot be interrupted, so on a slow device (llvmpipe renders ~0.35 M samples/s)
// even one sample per pixel at full resolution would freeze the UI for seconds. The controller
// therefore learns the cost of one pixel-sample from measured passes and picks the largest
// resolution (smallest divisor) at which one sample fits the trace budget, then as many samples
// as fit. The divisor changes only with hysteresis, because a new size restarts accumulation.
// Pure logic: no GL, no clock; the caller measures.
#pragma once

#include <cstdint>

namespace glint {

struct FrameBudgetConfig {
  double frame_seconds = 0.025;  // whole UI frame target (40 fps, a margin above 30)
  double min_trace_seconds = 0.003;
  double trace_seconds = 0.015;  // per UI frame; adapted by record_frame to what the UI leaves
  int max_samples = 64;          // per frame, so that edits still feel immediate
  int max_divisor = 16;          // never coarser than 1/16 of the framebuffer per axis
  int min_divisor = 1;           // 1: full framebuffer resolution allowed
};

class FrameBudget {
 public:
  explicit FrameBudget(FrameBudgetConfig config = {}) : config_(config) {}

  const FrameBudgetConfig& config() const { return config_; }
  void set_config(const FrameBudgetConfig& config);

  // The resolution divisor for a framebuffer of this many pixels (1 = full resolution).
  int divisor() const { return divisor_; }
  // Samples per pixel to trace this frame at `pixels` trace pixels (>= 1).
  int samples(int64_t pixels) const;

  // Records a finished pass: `samples` per pixel over `pixels` pixels took `seconds`.
  // `full_pixels` is the framebuffer's pixel count (the divisor is chosen against it).
  void record(int samples, int64_t pixels, double seconds, int64_t full_pixels);

  // Records a whole UI frame and the part of it spent tracing: the trace budget becomes the
  // frame target minus the (smoothed) rest, so slow UI drawing leaves less time to trace.
  void record_frame(double frame_seconds, double trace_seconds);

  // Seconds per pixel-sample as currently estimated (0 before the first measurement).
  double cost() const { return cost_; }

 private:
  int wanted_divisor(int64_t full_pixels) const;

  FrameBudgetConfig config_;
  double cost_ = 0;
  double overhead_ = -1;
  int divisor_ = 4;      // a cautious start until the first measurement
  int pending_ = 0;      // the divisor the estimates keep asking for
  int pending_frames_ = 0;
};

}  // namespace glint
