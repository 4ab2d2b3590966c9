#include "editor/render_stats_history.h"

#include <algorithm>
#include <cmath>

namespace glint {

void TimeSeries::add(double t_s, double v) {
  t.push_back(t_s);
  value.push_back(v);
  if (t.size() > max_points) {
    const size_t drop = t.size() - max_points;
    t.erase(t.begin(), t.begin() + static_cast<std::ptrdiff_t>(drop));
    value.erase(value.begin(), value.begin() + static_cast<std::ptrdiff_t>(drop));
  }
}

void TimeSeries::clear() {
  t.clear();
  value.clear();
}

void RenderStatsHistory::record(const FrameStats& stats, double now_s) {
  if (start_s < 0 || stats.restarted || stats.spp < last_spp) {
    start_s = now_s;
    samples_per_second.clear();
    estimated_error.clear();
    last_spp = 0;
  }
  const bool advanced = stats.spp > last_spp;
  last_spp = stats.spp;
  if (advanced) samples_per_second.add(now_s - start_s, stats.spp_per_second);
  // The viewport refreshes its estimate a few times a second: one point per new value.
  if (stats.estimated_relmse > 0 &&
      (estimated_error.empty() || estimated_error.value.back() != stats.estimated_relmse))
    add_error(now_s, stats.estimated_relmse);
}

std::optional<LogRange> log_axis_range(const TimeSeries& series) {
  double lo = 0, hi = 0;
  for (double v : series.value) {
    if (!(v > 0) || !std::isfinite(v)) continue;
    lo = lo > 0 ? std::min(lo, v) : v;
    hi = std::max(hi, v);
  }
  if (!(lo > 0)) return std::nullopt;
  lo /= 1.5;
  hi *= 1.5;
  if (hi < 10 * lo) {  // one value, or nearly: a decade around their middle
    const double mid = std::sqrt(lo * hi);
    lo = mid / std::sqrt(10.0);
    hi = mid * std::sqrt(10.0);
  }
  return LogRange{lo, hi};
}

void RenderStatsHistory::add_error(double now_s, double error) {
  if (start_s < 0) start_s = now_s;
  estimated_error.add(now_s - start_s, error);
}

}  // namespace glint
