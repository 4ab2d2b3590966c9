// The viewport's samples per pixel per second, over windows of wall-clock time. A pass traced
// in bands over many frames adds its samples only when it ends, so a window closes once it
// holds samples (and at least kMinSeconds have passed): the rate is then the pass's samples over
// the whole time it took, not 0 for the frames in between. A window with no samples at all
// closes after kIdleSeconds and reports 0 (a paused or stalled viewport).
#pragma once

#include <cstdint>

namespace glint {

struct SampleRate {
  static constexpr double kMinSeconds = 0.5;
  static constexpr double kIdleSeconds = 5.0;
  double per_second = 0;     // the last closed window's rate
  int64_t samples = 0;       // samples per pixel added in the open window
  double start_s = -1;       // when the open window started; < 0 before the first frame
  // Samples per pixel that ended in this frame.
  void add(int64_t spp) { samples += spp; }
  // Once per frame, after add: closes the window when it is due.
  void update(double now_s) {
    if (start_s < 0) start_s = now_s;
    const double span = now_s - start_s;
    if (span < kMinSeconds || (samples == 0 && span < kIdleSeconds)) return;
    per_second = double(samples) / span;
    samples = 0;
    start_s = now_s;
  }
};

}  // namespace glint
