#include "app/progress_bar.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace glint {

std::string format_progress(double done, int64_t total, double seconds, const char* unit,
                            int bar_width) {
  double fraction = total > 0 ? done / static_cast<double>(total) : 0.0;
  fraction = fraction < 0 ? 0 : (fraction > 1 ? 1 : fraction);
  int filled = static_cast<int>(std::lround(fraction * bar_width));
  std::string bar = "[" + std::string(filled, '#') + std::string(bar_width - filled, ' ') + "]";
  double rate = seconds > 0 ? done / seconds : 0.0;
  const long long whole = static_cast<long long>(std::floor(done));
  char tail[128];
  if (rate > 0 && done < total) {
    long eta = std::lround((static_cast<double>(total) - done) / rate);
    std::snprintf(tail, sizeof tail, " %lld/%lld %s  %.1f %s/s  ETA %ld:%02ld",
                  whole, static_cast<long long>(total), unit, rate, unit, eta / 60, eta % 60);
  } else {
    std::snprintf(tail, sizeof tail, " %lld/%lld %s  %.1f %s/s  %.1f s",
                  whole, static_cast<long long>(total), unit, rate, unit, seconds);
  }
  return bar + tail;
}

std::string format_time_progress(double seconds, double budget, int64_t samples, int bar_width) {
  double fraction = budget > 0 ? std::min(1.0, seconds / budget) : 1.0;
  int filled = static_cast<int>(std::lround(fraction * bar_width));
  std::string bar = "[" + std::string(filled, '#') + std::string(bar_width - filled, ' ') + "]";
  char tail[128];
  std::snprintf(tail, sizeof tail, " %.1f/%.1f s  %lld spp  %.1f spp/s", seconds, budget,
                static_cast<long long>(samples), seconds > 0 ? samples / seconds : 0.0);
  return bar + tail;
}

std::string format_error_estimate(double estimated_relmse, double target) {
  if (!(estimated_relmse >= 0)) return "";
  char text[80];
  if (target > 0)
    std::snprintf(text, sizeof text, "  est. relMSE %.2e (target %.2e)", estimated_relmse, target);
  else
    std::snprintf(text, sizeof text, "  est. relMSE %.2e", estimated_relmse);
  return text;
}

}  // namespace glint
