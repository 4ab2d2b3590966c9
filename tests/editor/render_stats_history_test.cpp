// The Render statistics panel's series: samples per second and the estimated error per frame,
// restarted with the accumulation.
#include "editor/render_stats_history.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

FrameStats stats_at(long long spp, double estimate, bool restarted = false) {
  FrameStats s;
  s.spp = spp;
  s.spp_per_second = 10;
  s.estimated_relmse = estimate;
  s.restarted = restarted;
  return s;
}

TEST(RenderStatsHistory, RecordsOneErrorPointPerNewEstimate) {
  RenderStatsHistory h;
  h.record(stats_at(1, -1), 100.0);  // no estimate yet
  EXPECT_TRUE(h.estimated_error.empty());
  h.record(stats_at(2, 0.5), 100.5);
  h.record(stats_at(3, 0.5), 101.0);  // the same estimate, not refreshed yet
  h.record(stats_at(4, 0.25), 101.5);
  ASSERT_EQ(h.estimated_error.value.size(), 2u);
  EXPECT_DOUBLE_EQ(h.estimated_error.value[1], 0.25);
  EXPECT_DOUBLE_EQ(h.estimated_error.t[1], 1.5);
  EXPECT_EQ(h.samples_per_second.t.size(), 4u);
}

TEST(RenderStatsHistory, ARestartStartsEverySeriesAgain) {
  RenderStatsHistory h;
  h.record(stats_at(8, 0.1), 10.0);
  h.record(stats_at(1, 0.9, /*restarted=*/true), 12.0);
  ASSERT_EQ(h.estimated_error.value.size(), 1u);
  EXPECT_DOUBLE_EQ(h.estimated_error.t[0], 0.0);
  EXPECT_DOUBLE_EQ(h.estimated_error.value[0], 0.9);
}

// Paused (a target reached, an export running): the spp stand still and so do the curves, which
// would otherwise scroll a flat zero line.
TEST(RenderStatsHistory, PausedFramesAddNoPoints) {
  RenderStatsHistory h;
  h.record(stats_at(4, 0.2), 1.0);
  FrameStats paused = stats_at(4, 0.2);
  paused.spp_per_second = 0;
  for (int i = 0; i < 50; ++i) h.record(paused, 1.1 + 0.1 * i);
  EXPECT_EQ(h.samples_per_second.t.size(), 1u);
  EXPECT_EQ(h.estimated_error.t.size(), 1u);
  h.record(stats_at(5, 0.1), 7.0);  // tracing again
  EXPECT_EQ(h.samples_per_second.t.size(), 2u);
}

// The error plot's log axis: from the positive values only, never degenerate.
TEST(RenderStatsHistory, LogAxisRangeIgnoresZeroAndAbsentValues) {
  TimeSeries s{"error"};
  EXPECT_FALSE(log_axis_range(s));  // after a restart: no values yet
  s.add(0, 0);
  EXPECT_FALSE(log_axis_range(s));  // zero has no place on a log axis
  s.add(1, 2e-3);  // one estimate: a decade around it
  auto one = log_axis_range(s);
  ASSERT_TRUE(one);
  EXPECT_LT(one->lo, 2e-3);
  EXPECT_GT(one->hi, 2e-3);
  EXPECT_NEAR(one->hi / one->lo, 10, 1e-9);
  EXPECT_GT(one->lo, 1e-4);
  s.add(2, 5e-5);
  s.add(3, -1);
  auto two = log_axis_range(s);
  ASSERT_TRUE(two);
  EXPECT_LT(two->lo, 5e-5);
  EXPECT_GT(two->lo, 1e-5);
  EXPECT_GT(two->hi, 2e-3);
  EXPECT_LT(two->hi, 1e-2);
}

}  // namespace
}  // namespace glint
