// RenderSession: a sample target hit exactly, checkpoints hit exactly, a time target, the batch
// policy and cancellation, on a small scene.
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <vector>

#include "gl_test_support.h"
#include "renderer/project_file.h"
#include "renderer/render_session.h"

namespace glint {
namespace {

constexpr double kAlways = std::numeric_limits<double>::infinity();

struct SessionTest : ::testing::Test {
  void SetUp() override {
    Scene scene = test::empty_scene();
    scene.environment.color = {0.5f, 0.5f, 0.5f};
    scene.materials.push_back({.name = "white", .color = {0.8f, 0.8f, 0.8f}});
    scene.spheres.push_back({.name = "ball", .center = {0, 0, 0}, .radius = 1, .material = "white"});
    renderer.sync(scene, 8, 8);
  }
  // The sample count after every pass of run().
  std::vector<int64_t> run(RenderSession& session) {
    std::vector<int64_t> counts;
    session.run([&](RenderSession& s) { counts.push_back(s.samples()); });
    return counts;
  }
  bool context = (test::ensure_gl_context(), true);  // before the renderer
  GpuRenderer renderer;
};

// A batch that doubles after every pass (grow_below infinite) is capped by the target.
TEST_F(SessionTest, SampleTargetIsHitExactly) {
  RenderSessionOptions o;
  o.target.samples = 1000;
  o.batch.grow_below = kAlways;
  RenderSession session(renderer, o);
  EXPECT_EQ(run(session), (std::vector<int64_t>{1, 3, 7, 15, 31, 63, 127, 255, 511, 1000}));
  EXPECT_TRUE(session.done());
  EXPECT_FALSE(session.cancelled());
  EXPECT_EQ(renderer.sample_count(), 1000);
  EXPECT_EQ(session.progress(), 1.0f);
  EXPECT_GT(session.seconds(), 0.0);
  EXPECT_EQ(session.step(), 0);  // done: nothing more is traced
  EXPECT_EQ(renderer.sample_count(), 1000);
}

TEST_F(SessionTest, BatchStopsAtItsMaximumAndHalvesAfterSlowPasses) {
  RenderSessionOptions o;
  o.target.samples = 40;
  o.batch.grow_below = kAlways;
  o.batch.max_batch = 8;
  RenderSession grows(renderer, o);
  EXPECT_EQ(run(grows), (std::vector<int64_t>{1, 3, 7, 15, 23, 31, 39, 40}));

  renderer.sync(test::empty_scene(), 8, 8);  // a new scene: the accumulation restarts at 0
  ASSERT_EQ(renderer.sample_count(), 0);
  o.target.samples = 10;
  o.batch = {.first_batch = 8, .max_batch = 8, .grow_below = 0, .shrink_above = 0};  // every pass is "slow"
  RenderSession shrinks(renderer, o);
  EXPECT_EQ(run(shrinks), (std::vector<int64_t>{8, 10}));  // 8, then the halved batch capped at the target
}

// Growing by rate, the second pass is the batch that the first one's rate says fits in
// grow_below seconds (here far more than max_batch, which caps it), not twice the first.
TEST_F(SessionTest, BatchGrownByRateJumpsToTheBatchThatFits) {
  RenderSessionOptions o;
  o.target.samples = 200;
  o.batch = {.first_batch = 1, .max_batch = 64, .grow_below = 1e9, .grow_by_rate = true};
  RenderSession jumps(renderer, o);
  EXPECT_EQ(run(jumps), (std::vector<int64_t>{1, 65, 129, 193, 200}));

  renderer.sync(test::empty_scene(), 8, 8);
  o.batch.grow_by_rate = false;  // doubling, for comparison
  RenderSession doubles(renderer, o);
  EXPECT_EQ(run(doubles), (std::vector<int64_t>{1, 3, 7, 15, 31, 63, 127, 191, 200}));
}

// With an error target, a batch grown by rate goes no further than the minimum sample count
// before the first estimate: after one sample nothing is known, so the second pass ends at 16,
// not at 1 + max_batch; after it the estimate caps the passes (here a target never met).
TEST_F(SessionTest, ErrorTargetPassesStopAtTheMinimumBeforeAnEstimate) {
  renderer.sync(load_project(GLINT_SOURCE_DIR "/projects/cornell_box.glint"), 8, 8);
  RenderSessionOptions o;
  o.target = {.samples = 200, .seconds = 0, .error = 1e-12};
  o.batch = {.first_batch = 1, .max_batch = 64, .grow_below = 1e9, .grow_by_rate = true};
  RenderSession session(renderer, o);
  const std::vector<int64_t> passes = run(session);
  ASSERT_GE(passes.size(), 3u);
  EXPECT_EQ(passes[0], 1);
  EXPECT_EQ(passes[1], kErrorTargetMinSamples);
  EXPECT_GT(passes[2], kErrorTargetMinSamples);
  EXPECT_EQ(passes.back(), 200);
  EXPECT_EQ(session.stop_reason(), StopReason::samples);
}

// Every power of two and the target are reached exactly, whatever the batch; passes between
// them are not checkpoints.
TEST_F(SessionTest, CheckpointsAreHitExactly) {
  RenderSessionOptions o;
  o.target.samples = 20;
  o.batch.grow_below = kAlways;
  o.batch.max_batch = 4;
  o.checkpoints = true;
  RenderSession session(renderer, o);
  std::vector<int64_t> checkpoints, others;
  session.run([&](RenderSession& s) { (s.at_checkpoint() ? checkpoints : others).push_back(s.samples()); });
  EXPECT_EQ(checkpoints, (std::vector<int64_t>{1, 2, 4, 8, 16, 20}));
  EXPECT_EQ(others, (std::vector<int64_t>{12}));
}

// step() with time to spare still returns at a checkpoint, so that the caller sees it.
TEST_F(SessionTest, StepReturnsAtACheckpoint) {
  RenderSessionOptions o;
  o.target.samples = 64;
  o.batch.grow_below = kAlways;
  o.checkpoints = true;
  RenderSession session(renderer, o);
  EXPECT_EQ(session.step(60.0), 1);
  EXPECT_TRUE(session.at_checkpoint());
  EXPECT_EQ(session.step(60.0), 1);
  EXPECT_EQ(session.samples(), 2);
}

// A time target traces until its seconds are spent: the last pass started before them.
TEST_F(SessionTest, TimeTargetStopsAfterItsTime) {
  RenderSessionOptions o;
  o.target = {.samples = 0, .seconds = 0.2};
  o.batch.max_batch = 1;
  o.checkpoints = true;  // powers of two only
  RenderSession session(renderer, o);
  double before_last_pass = 0;
  std::vector<int64_t> checkpoints;
  while (!session.done()) {
    before_last_pass = session.seconds();
    EXPECT_LT(session.progress(), 1.0f);
    session.step();
    if (session.at_checkpoint()) checkpoints.push_back(session.samples());
  }
  EXPECT_GE(session.seconds(), 0.2);
  EXPECT_LT(before_last_pass, 0.2);
  EXPECT_EQ(session.samples(), renderer.sample_count());
  EXPECT_GT(session.samples(), 0);
  EXPECT_EQ(session.progress(), 1.0f);
  ASSERT_FALSE(checkpoints.empty());
  for (size_t i = 0; i < checkpoints.size(); ++i) EXPECT_EQ(checkpoints[i], int64_t(1) << i);
}

TEST_F(SessionTest, CancelStopsTracing) {
  RenderSessionOptions o;
  o.target.samples = 1000;
  o.batch.max_batch = 1;
  RenderSession session(renderer, o);
  session.run([](RenderSession& s) {
    if (s.samples() == 5) s.cancel();
  });
  EXPECT_TRUE(session.cancelled());
  EXPECT_TRUE(session.done());
  EXPECT_EQ(renderer.sample_count(), 5);
  EXPECT_EQ(session.step(1.0), 0);
  EXPECT_EQ(renderer.sample_count(), 5);
  EXPECT_LT(session.progress(), 0.01f);
}

// run(slice, on_step) calls back after every step, also one that ends inside a tiled pass
// (`glint render`'s progress line while a long pass runs); on_step may cancel mid-pass.
TEST_F(SessionTest, RunWithASliceCallsBackAfterEveryBand) {
  RenderSessionOptions o;
  o.target.samples = 3;
  o.batch.max_batch = 1;
  o.tiled = true;
  o.band_rows = 2;  // a slice of 0: one band of 2 of the 8 rows per step
  RenderSession session(renderer, o);
  std::vector<double> traced;
  session.run(0.0, [&](RenderSession& s) { traced.push_back(s.traced_samples()); });
  ASSERT_EQ(traced.size(), 12u);
  for (size_t i = 0; i < traced.size(); ++i) EXPECT_DOUBLE_EQ(traced[i], 0.25 * double(i + 1)) << i;
  EXPECT_EQ(renderer.sample_count(), 3);
  EXPECT_EQ(session.stop_reason(), StopReason::samples);

  renderer.sync(test::empty_scene(), 8, 8);
  RenderSession cancelled(renderer, o);
  int steps = 0;
  cancelled.run(0.0, [&](RenderSession& s) {
    if (++steps == 6) s.cancel();  // half-way through the second pass
  });
  EXPECT_EQ(steps, 6);
  EXPECT_TRUE(cancelled.cancelled());
  EXPECT_EQ(renderer.sample_count(), 1);
}

TEST_F(SessionTest, NeedsATarget) {
  RenderSessionOptions o;
  o.target.samples = 0;
  EXPECT_THROW(RenderSession(renderer, o), std::invalid_argument);
}

}  // namespace
}  // namespace glint
