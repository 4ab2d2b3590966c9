// The frame-time controller as pure logic: simulated devices of known cost.
#include <gtest/gtest.h>

#include <algorithm>

#include "editor/frame_budget.h"

namespace glint {
namespace {

// Runs frames of a device that needs `cost` seconds per pixel-sample at a framebuffer of
// full_pixels; returns the trace seconds of the last frame.
double simulate(FrameBudget& b, double cost, int64_t full_pixels, int frames) {
  double seconds = 0;
  for (int i = 0; i < frames; ++i) {
    int64_t pixels = full_pixels / (int64_t(b.divisor()) * b.divisor());
    int k = b.samples(pixels);
    seconds = cost * k * pixels;
    b.record(k, pixels, seconds, full_pixels);
  }
  return seconds;
}

TEST(FrameBudget, SlowDeviceGetsACoarserPreviewWithinTheBudget) {
  // llvmpipe-like: 0.35 M samples/s over a 700x750 viewport (one full sample takes 1.5 s).
  FrameBudget b;
  const int64_t full = 700 * 750;
  double last = simulate(b, 1 / 0.35e6, full, 50);
  EXPECT_GT(b.divisor(), 2);
  EXPECT_LE(last, b.frame_trace_seconds() * 1.0001);
  EXPECT_LE(b.frame_trace_seconds(), b.config().drag_frame_seconds);
  EXPECT_LE(b.divisor(), b.config().max_divisor);
}

// Where the 25 ms frame target would leave a drag's preview at 1/7 (blocks nobody can read), a
// quarter resolution that fits the drag's longer frames (about 11 fps) is used instead; the UI's
// own time per frame counts against it.
TEST(FrameBudget, DragKeepsAQuarterResolutionWhereItFitsTenFramesASecond) {
  const int64_t full = 700 * 600;
  const double cost = 1.0 / full;  // one sample per pixel at full resolution: 1 s
  FrameBudget b;
  double last = simulate(b, cost, full, 50);
  EXPECT_EQ(b.divisor(), 4);
  EXPECT_GT(last, b.config().trace_seconds);  // longer than the fluid target...
  EXPECT_LE(last, b.config().drag_frame_seconds);  // ...within the drag's frame
  // 30 ms of UI per frame leaves the drag 60 ms: 1/5 then.
  FrameBudget busy;
  for (int i = 0; i < 80; ++i) {
    const double traced = simulate(busy, cost, full, 1);
    busy.record_frame(0.030 + traced, traced);
  }
  EXPECT_EQ(busy.divisor(), 5);
  // Where the UI alone takes 100 ms a frame (a loaded machine), the drag still traces 40 ms.
  FrameBudget loaded;
  for (int i = 0; i < 80; ++i) {
    const double traced = simulate(loaded, cost, full, 1);
    loaded.record_frame(0.100 + traced, traced);
  }
  EXPECT_DOUBLE_EQ(loaded.frame_trace_seconds(), loaded.config().drag_min_trace_seconds);
  EXPECT_EQ(loaded.divisor(), 5);
  EXPECT_LE(cost * double(full) / (double(busy.divisor()) * busy.divisor()), busy.frame_trace_seconds() * 1.0001);
  // A device quick enough for the fluid target keeps it.
  FrameBudget quick;
  simulate(quick, cost / 40, full, 50);
  EXPECT_LE(quick.divisor(), 2);
  EXPECT_DOUBLE_EQ(quick.frame_trace_seconds(), quick.config().trace_seconds);
}

TEST(FrameBudget, FastDeviceTracesFullResolutionWithManySamples) {
  FrameBudget b;
  const int64_t full = 1920 * 1080;
  double last = simulate(b, 1e-10, full, 50);  // 10 G samples/s
  EXPECT_EQ(b.divisor(), 1);
  EXPECT_GT(b.samples(full), 10);
  EXPECT_LE(b.samples(full), b.config().max_samples);
  EXPECT_LE(last, b.frame_trace_seconds() * 1.0001);
}

TEST(FrameBudget, DivisorIsStableUnderNoise) {
  // Measurements jittering by +-10% around a cost where the divisor sits near a boundary must
  // not flip the resolution (each flip restarts the accumulation).
  FrameBudget b;
  const int64_t full = 800 * 600;
  simulate(b, 2e-7, full, 30);
  int settled = b.divisor();
  int changes = 0;
  for (int i = 0; i < 200; ++i) {
    double cost = 2e-7 * (i % 2 ? 1.1 : 0.9);
    int64_t pixels = full / (int64_t(b.divisor()) * b.divisor());
    int k = b.samples(pixels);
    int before = b.divisor();
    b.record(k, pixels, cost * k * pixels, full);
    changes += b.divisor() != before;
  }
  EXPECT_LE(changes, 1);
  EXPECT_NEAR(b.divisor(), settled, 1);
}

TEST(FrameBudget, SlowdownCoarsensAtOnceSpeedupRefinesAfterAWhile) {
  FrameBudget b;
  const int64_t full = 640 * 480;
  simulate(b, 1e-9, full, 30);
  ASSERT_EQ(b.divisor(), 1);
  // A heavy scene: the very next frame must already be coarser.
  b.record(1, full, 1e-6 * full, full);
  int coarse = b.divisor();
  EXPECT_GT(coarse, 1);
  // Cheap again: refines, but only after several consistent frames.
  int64_t pixels = full / (int64_t(coarse) * coarse);
  b.record(1, pixels, 1e-9 * pixels, full);
  EXPECT_EQ(b.divisor(), coarse);
  simulate(b, 1e-9, full, 30);
  EXPECT_EQ(b.divisor(), 1);
}

TEST(FrameBudget, UiOverheadShrinksTheTraceBudget) {
  FrameBudget b;
  for (int i = 0; i < 100; ++i) b.record_frame(0.030, 0.010);  // 20 ms of UI per frame
  EXPECT_NEAR(b.config().trace_seconds, b.config().frame_seconds - 0.020, 1e-3);
  for (int i = 0; i < 100; ++i) b.record_frame(0.100, 0.0);  // UI alone over the target
  EXPECT_DOUBLE_EQ(b.config().trace_seconds, b.config().min_trace_seconds);
}

// A running export's slice: the trace budget where the UI is quick, twice the UI's time where
// it is slow (so the export gets two thirds of each frame), never more than 0.1 s.
TEST(FrameBudget, ExportSliceLeavesTheExportTwoThirdsOfASlowFrame) {
  FrameBudget quick;
  for (int i = 0; i < 200; ++i) quick.record_frame(0.012, 0.010);  // 2 ms of UI per frame
  EXPECT_NEAR(quick.export_slice_seconds(), quick.config().trace_seconds, 1e-12);
  EXPECT_NEAR(quick.export_slice_seconds(), 0.023, 1e-3);
  FrameBudget slow;
  for (int i = 0; i < 200; ++i) slow.record_frame(0.033, 0.003);  // 30 ms of UI per frame
  EXPECT_NEAR(slow.export_slice_seconds(), 0.060, 1e-3);
  FrameBudget very_slow;
  for (int i = 0; i < 200; ++i) very_slow.record_frame(0.5, 0.0);
  EXPECT_DOUBLE_EQ(very_slow.export_slice_seconds(), FrameBudget::kMaxExportSliceSeconds);
  EXPECT_DOUBLE_EQ(FrameBudget().export_slice_seconds(), FrameBudget().config().trace_seconds);
}

TEST(FrameBudget, IgnoresMeaninglessMeasurements) {
  FrameBudget b;
  b.record(0, 100, 1.0, 100);
  b.record(1, 0, 1.0, 100);
  b.record(1, 100, 0.0, 100);
  EXPECT_EQ(b.cost(), 0);
  EXPECT_EQ(b.samples(1000), 1);
}

// The automatic preview over simulated frames of a device of known cost: returns the level.
struct PreviewSim {
  PreviewSim(double c, int64_t f) : cost(c), full(f) {}
  FrameBudget budget;
  PreviewResolution preview;
  double cost;
  int64_t full;
  double now = 0;
  int64_t samples = 0;
  int restarts = 0;
  int traced_frames = 0;

  // One frame: `changed` is an edit (the sync restarted), `active` the user's input.
  void frame(bool changed, bool active) {
    PreviewFrame f{changed, active, now, changed ? 0 : samples, full};
    const int before = preview.divisor();
    const int d = preview.update(budget, f);
    if (changed || d != before) {
      samples = 0;
      ++restarts;
    }
    const int64_t pixels = full / (int64_t(d) * d);
    f.samples = samples;
    const int k = preview.samples(budget, f, pixels);
    double seconds = 0.005;  // the UI's own part of the frame
    if (k > 0) {
      budget.record(k, pixels, cost * k * pixels, full);
      samples += k;
      seconds += cost * k * pixels;
      ++traced_frames;
    }
    now += seconds;
  }
};

TEST(PreviewResolution, IdleRefinesToFullResolutionWhereAPassFitsTheRefineLimit) {
  // A fast device: every level fits; idle refinement reaches full resolution.
  PreviewSim fast(1e-10, 1920 * 1080);
  fast.frame(true, false);
  for (int i = 0; i < 400 && fast.preview.divisor() > 1; ++i) fast.frame(false, false);
  EXPECT_EQ(fast.preview.divisor(), 1);
  // llvmpipe-like (0.35 M samples/s) in a 700x750 viewport: a full-resolution pass takes 1.5 s,
  // traced in bands by the viewport; idle refinement goes all the way.
  PreviewSim slow(1 / 0.35e6, 700 * 750);
  for (int i = 0; i < 10; ++i) slow.frame(true, false);  // the budget learns the cost
  EXPECT_GT(slow.preview.divisor(), 1);
  for (int i = 0; i < 400; ++i) slow.frame(false, false);
  EXPECT_EQ(slow.preview.divisor(), 1);
  // A 2560x1600 viewport on it: 11.7 s a pass at full resolution; it stops at the finest level
  // whose pass fits refine_max_pass_seconds.
  PreviewSim huge(1 / 0.35e6, 2560 * 1600);
  for (int i = 0; i < 10; ++i) huge.frame(true, false);
  for (int i = 0; i < 400; ++i) huge.frame(false, false);
  const int d = huge.preview.divisor();
  const double limit = huge.budget.config().refine_max_pass_seconds;
  EXPECT_LE(huge.cost * double(huge.full) / (double(d) * d), limit);
  const int finer = std::max(1, d / 2);
  EXPECT_TRUE(d == 1 || huge.cost * double(huge.full) / (double(finer) * finer) > limit);
}

TEST(PreviewResolution, OnlyEditsAndRefinementChangeTheLevel) {
  PreviewSim sim(1 / 0.35e6, 700 * 750);
  sim.frame(true, false);
  for (int i = 0; i < 400; ++i) sim.frame(false, false);
  const int refined = sim.preview.divisor();
  const int restarts = sim.restarts;
  // Input without edits (hovering, clicks that select, the exposure drag): same level, no
  // restart, and the accumulation is kept.
  const int64_t kept = sim.samples;
  for (int i = 0; i < 50; ++i) sim.frame(false, true);
  EXPECT_EQ(sim.preview.divisor(), refined);
  EXPECT_EQ(sim.restarts, restarts);
  EXPECT_GE(sim.samples, kept);
  // An edit: back to the fluid level at once, where each frame fits the frame budget.
  sim.frame(true, true);
  EXPECT_EQ(sim.preview.divisor(), sim.budget.divisor());
  EXPECT_GT(sim.preview.divisor(), refined);
  for (int i = 0; i < 20; ++i) sim.frame(true, true);
  EXPECT_LE(sim.cost * double(sim.full) / (double(sim.preview.divisor()) * sim.preview.divisor()),
            sim.budget.frame_trace_seconds() * 1.0001);
}

TEST(PreviewResolution, ALevelTooSlowForAnIdleFrameGoesBackToFluid) {
  // The first frame's guess (before any measurement) on a slow device (a heavy scene) in a large
  // viewport: one pass at that level would take 13 s.
  PreviewSim sim(1 / 0.02e6, 2560 * 1600);
  sim.frame(true, false);
  const int guess = sim.preview.divisor();
  for (int i = 0; i < 5; ++i) sim.frame(false, false);
  EXPECT_GT(sim.preview.divisor(), guess);
  const int d = sim.preview.divisor();
  EXPECT_LE(sim.cost * double(sim.full) / (double(d) * d), 1.5 * sim.budget.config().refine_max_pass_seconds);
}

TEST(PreviewResolution, AtTheFluidLevelInputNeverPausesTheAccumulation) {
  PreviewSim sim(1 / 0.35e6, 700 * 750);
  sim.frame(true, false);
  for (int i = 0; i < 30; ++i) sim.frame(true, true);  // settle the budget while editing
  const int traced = sim.traced_frames;
  for (int i = 0; i < 30; ++i) sim.frame(false, true);  // e.g. dragging the exposure
  EXPECT_EQ(sim.traced_frames, traced + 30);
}

}  // namespace
}  // namespace glint
