// Wall-clock seconds since a moment, on the monotonic clock: how every timing in Glint is taken
// (passes, bands, back-end timing, program builds, denoising, the export's frames).
#pragma once

#include <chrono>

namespace glint {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace glint
