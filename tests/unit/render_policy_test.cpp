// The render policy of `glint render` (renderer/render_policy.h): the back end for an image's
// size, and the passes and bands of a batch render, without a GL context.
#include <gtest/gtest.h>

#include "renderer/render_policy.h"

namespace glint {
namespace {

TEST(RenderPolicy, SmallImagesOnLlvmpipeTakeTheComputeShader) {
  // 24x24 is one 64x64 tile: fewer than 2 threads' worth.
  const BackendForImage small = backend_for_image(TraceBackend::fragment, 24, 24, true, 2);
  EXPECT_EQ(small.backend, TraceBackend::compute);
  EXPECT_EQ(small.reason, "compute for an image of fewer 64x64 llvmpipe tiles than its 2 threads");
  // Enough tiles, another driver, or compute chosen already: the device's choice, no reason.
  for (const BackendForImage& kept :
       {backend_for_image(TraceBackend::fragment, 128, 128, true, 2),
        backend_for_image(TraceBackend::fragment, 24, 24, false, 2)}) {
    EXPECT_EQ(kept.backend, TraceBackend::fragment);
    EXPECT_EQ(kept.reason, "");
  }
  const BackendForImage compute = backend_for_image(TraceBackend::compute, 24, 24, true, 2);
  EXPECT_EQ(compute.backend, TraceBackend::compute);
  EXPECT_EQ(compute.reason, "");
}

TEST(RenderPolicy, SampleTargetsGetLongPassesInBandsOfTileRows) {
  const RenderTarget target{256, 0, 0};
  const SessionPlan plan = batch_session_plan(target, false, true, 1920, 1080, 2);
  EXPECT_EQ(plan.options.target.samples, 256);
  EXPECT_TRUE(plan.options.checkpoints);
  EXPECT_TRUE(plan.options.tiled);
  EXPECT_EQ(plan.options.band_rows, band_rows_for_threads(1920, 2));
  EXPECT_EQ(plan.options.band_rows % kLlvmpipeTileSize, 0);
  EXPECT_TRUE(plan.options.batch.grow_by_rate);
  EXPECT_EQ(plan.options.batch.grow_below, kPassSeconds);
  EXPECT_EQ(plan.options.batch.first_batch, 1);  // 2 Mpixels: one sample is kFirstPassPixelSamples already
  EXPECT_EQ(plan.step_seconds, kBandSeconds);

  // An image of one band: untiled, shorter passes; a first pass of about kFirstPassPixelSamples
  // samples (at most 16 per pixel).
  const SessionPlan small = batch_session_plan(target, false, false, 64, 64, 2);
  EXPECT_FALSE(small.options.tiled);
  EXPECT_EQ(small.options.batch.grow_below, kUntiledPassSeconds);
  EXPECT_EQ(small.options.batch.first_batch, 16);
  EXPECT_EQ(batch_session_plan(target, false, false, 128, 128, 2).options.batch.first_batch, 8);
  EXPECT_EQ(small.step_seconds, kBandSeconds);
}

TEST(RenderPolicy, TimeTargetsAndAdaptiveSamplingStartAtOneSampleUntiled) {
  for (const SessionPlan& plan : {batch_session_plan({0, 2.0, 0}, false, false, 1920, 1080, 2),
                                  batch_session_plan({64, 0, 0}, true, false, 1920, 1080, 2)}) {
    EXPECT_FALSE(plan.options.tiled);
    EXPECT_EQ(plan.options.band_rows, 1);
    EXPECT_FALSE(plan.options.batch.grow_by_rate);
    EXPECT_EQ(plan.options.batch.first_batch, 1);
    EXPECT_EQ(plan.options.batch.grow_below, BatchPolicy{}.grow_below);
    EXPECT_EQ(plan.step_seconds, 0.0);
  }
}

}  // namespace
}  // namespace glint
