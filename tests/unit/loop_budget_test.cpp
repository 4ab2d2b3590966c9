// The draw size that keeps the trace shader under Mesa llvmpipe's loop limit (loop_budget.h).
#include <gtest/gtest.h>

#include "renderer/loop_budget.h"

namespace glint {
namespace {

TEST(LoopBudget, DrawsStayUnderAQuarterOfTheLimit) {
  for (long shapes : {0L, 7L, 12L, 100L, 1000L})
    for (int bounces : {0, 1, 8, 64}) {
      const int n = samples_per_draw(shapes, bounces);
      EXPECT_GE(n, 1);
      EXPECT_LE(n, 64);
      if (n > 1) EXPECT_LE(n * loop_iterations_per_sample(shapes, bounces), kLlvmpipeLoopLimit / 4) << shapes << " " << bounces;
    }
  // The default project (7 shapes, 8 bounces): passes of 1000 samples broke, 100 did not.
  EXPECT_LT(samples_per_draw(7, 8) * 10, 1000);
}

TEST(LoopBudget, ThousandsOfShapesExceedTheLimitInOneSample) {
  EXPECT_LT(loop_iterations_per_sample(100, 8), kLlvmpipeLoopLimit);
  EXPECT_GT(loop_iterations_per_sample(5000, 8), kLlvmpipeLoopLimit);
  EXPECT_EQ(samples_per_draw(5000, 8), 1);
}

}  // namespace
}  // namespace glint
