// The draw size that keeps the trace shader under Mesa llvmpipe's loop limit (loop_budget.h).
#include <gtest/gtest.h>

#include "renderer/bvh.h"
#include "renderer/loop_budget.h"

namespace glint {
namespace {

TEST(LoopBudget, DrawsStayUnderAQuarterOfTheLimit) {
  for (long shapes : {0L, 7L, 12L, 100L, 1000L})
    for (int bounces : {0, 1, 8, 64}) {
      const int n = samples_per_draw_for(loop_iterations_per_sample(shapes, bounces));
      EXPECT_GE(n, 1);
      EXPECT_LE(n, 64);
      if (n > 1) {
        EXPECT_LE(n * loop_iterations_per_sample(shapes, bounces), kLlvmpipeLoopLimit / 4) << shapes << " " << bounces;
      }
    }
  // The default project (7 shapes, 8 bounces): passes of 1000 samples broke, 100 did not.
  EXPECT_LT(samples_per_draw_for(loop_iterations_per_sample(7, 8)) * 10, 1000);
}

TEST(LoopBudget, ThousandsOfShapesExceedTheLimitInOneSample) {
  EXPECT_LT(loop_iterations_per_sample(100, 8), kLlvmpipeLoopLimit);
  EXPECT_GT(loop_iterations_per_sample(5000, 8), kLlvmpipeLoopLimit);
  EXPECT_EQ(samples_per_draw_for(loop_iterations_per_sample(5000, 8)), 1);
}

// With the BVH the estimate uses the shader's traversal cap: one sample at the cap fits the
// limit wherever the cap is above its floor, so llvmpipe never cuts a traversal short unseen.
TEST(LoopBudget, BvhStepCapKeepsOneSampleWithinTheLimit) {
  for (int bounces : {0, 1, 4, 8, 12}) {
    const int steps = bvh_max_steps(kBvhMaxLeafSize, bounces);
    EXPECT_GE(steps, kMinBvhSteps);
    EXPECT_LE(bvh_loop_iterations_per_sample(steps, kBvhMaxLeafSize, bounces), kLlvmpipeLoopLimit) << bounces;
    // ... and it is the largest such cap (or the ceiling).
    if (steps < kMaxBvhSteps) {
      EXPECT_GT(bvh_loop_iterations_per_sample(steps + 1, kBvhMaxLeafSize, bounces), kLlvmpipeLoopLimit) << bounces;
    }
  }
  EXPECT_EQ(bvh_max_steps(kBvhMaxLeafSize, 8), 360);
  // Many bounces: the cap stays at its floor and the scene is reported as over the limit.
  EXPECT_EQ(bvh_max_steps(kBvhMaxLeafSize, 64), kMinBvhSteps);
  EXPECT_GT(bvh_loop_iterations_per_sample(kMinBvhSteps, kBvhMaxLeafSize, 64), kLlvmpipeLoopLimit);
}

TEST(LoopBudget, AutomaticChoiceTakesTheBvhWhereTheLoopCannotRender) {
  EXPECT_FALSE(use_bvh(Accel::automatic, 0, 8));
  EXPECT_FALSE(use_bvh(Accel::bvh, 0, 8));  // nothing to build it over
  EXPECT_FALSE(use_bvh(Accel::automatic, 7, 8));
  EXPECT_TRUE(use_bvh(Accel::automatic, kBvhCrossoverShapes, 8));
  EXPECT_FALSE(use_bvh(Accel::loop, 5000, 8));
  EXPECT_TRUE(use_bvh(Accel::bvh, 1, 8));
  // Below the crossover, but one sample of the loop would exceed the limit (many bounces).
  ASSERT_GT(loop_iterations_per_sample(20, 1000), kLlvmpipeLoopLimit);
  EXPECT_TRUE(use_bvh(Accel::automatic, 20, 1000));
}

}  // namespace
}  // namespace glint
