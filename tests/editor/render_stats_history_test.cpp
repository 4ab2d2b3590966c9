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

}  // namespace
}  // namespace glint
