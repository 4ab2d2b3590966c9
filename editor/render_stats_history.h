// What the Render statistics panel plots: figures of the viewport's accumulation against the
// time since it last restarted. No UI types: the panel (ui_stats.cpp) draws these series with
// ImPlot, and any producer (the frame statistics: samples per second and the viewport's
// estimated relMSE) adds points to a series of its own.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "editor/viewport_frame.h"

namespace glint {

// One curve: x is seconds since the accumulation started, y the value. Keeps the newest
// `max_points` points (the oldest go first).
struct TimeSeries {
  std::string label;
  std::vector<double> t, value;
  size_t max_points = 2000;

  void add(double t_s, double v);
  void clear();
  bool empty() const { return t.empty(); }
};

// The y range of a log axis for `series`: its positive finite values (zero, negative and absent
// ones have no place on it) with some room, at least a factor of 10 tall; nullopt when it has
// none (the plot then shows a fixed decade range instead of ImPlot's degenerate fit).
struct LogRange {
  double lo, hi;
};
std::optional<LogRange> log_axis_range(const TimeSeries& series);

// The panel's series. record() is called once per frame with that frame's statistics.
struct RenderStatsHistory {
  TimeSeries samples_per_second{"samples per pixel per second"};
  // The viewport's estimated relMSE (FrameStats::estimated_relmse) against time, one point per
  // new estimate; empty until the first estimate.
  TimeSeries estimated_error{"estimated error"};

  // Frame time `now_s` (any clock); a restart of the accumulation (or the first call) starts
  // every series again at t = 0. Frames that add no samples (paused at a target, during an
  // export, or inside a pass traced in bands) add no points: the curves stand still.
  void record(const FrameStats& stats, double now_s);
  // A point of the error series at `now_s` on the same clock as record().
  void add_error(double now_s, double error);
  double start_s = -1;  // clock time of the accumulation's start; < 0 before the first record
  long long last_spp = 0;
};

}  // namespace glint
