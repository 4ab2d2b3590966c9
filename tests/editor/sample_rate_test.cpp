#include "editor/sample_rate.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

TEST(SampleRate, APassTracedInBandsCountsOverTheWholeTimeItTook) {
  SampleRate rate;
  rate.update(0.0);
  // A 2 s pass of 4 samples per pixel traced in bands: nothing ends in the frames before.
  for (double t = 0.1; t < 2.0; t += 0.1) {
    rate.update(t);
    EXPECT_EQ(rate.per_second, 0.0) << "at " << t << " s no window may close without samples";
  }
  rate.add(4);
  rate.update(2.0);
  EXPECT_DOUBLE_EQ(rate.per_second, 2.0);  // 4 spp over 2 s, in the frame the pass ended
}

TEST(SampleRate, ShortPassesAverageOverHalfASecond) {
  SampleRate rate;
  rate.update(0.0);
  for (int frame = 1; frame <= 5; ++frame) {
    rate.add(1);
    rate.update(frame * 0.1);  // one sample per 0.1 s frame
  }
  EXPECT_NEAR(rate.per_second, 10.0, 1e-9);
}

TEST(SampleRate, AViewportThatStopsTracingFallsToZero) {
  SampleRate rate;
  rate.update(0.0);
  rate.add(3);
  rate.update(1.0);
  EXPECT_DOUBLE_EQ(rate.per_second, 3.0);
  rate.update(1.0 + SampleRate::kIdleSeconds - 0.1);
  EXPECT_DOUBLE_EQ(rate.per_second, 3.0);
  rate.update(1.0 + SampleRate::kIdleSeconds);
  EXPECT_DOUBLE_EQ(rate.per_second, 0.0);
}

}  // namespace
}  // namespace glint
