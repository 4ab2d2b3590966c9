// The display transform (shaders/lib/tonemap.glsl, docs/DESIGN.md §6) and the random numbers
// (shaders/lib/rng.glsl), in float and double.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "shader_test_util.h"

namespace glint::shader_test {
namespace {

template <class L>
class ShaderTonemap : public ::testing::Test {};
TYPED_TEST_SUITE(ShaderTonemap, Precisions, PrecisionName);

template <class L>
class ShaderRng : public ::testing::Test {};
TYPED_TEST_SUITE(ShaderRng, Precisions, PrecisionName);

// docs/DESIGN.md §6, written out independently: exposure in stops scales c, then the filmic curve
// f(c) = (0.9c^2 + 0.02c) / (0.87c^2 + 0.35c + 0.14) (or nothing for linear), then a clamp to
// [0, 1] for display, then gamma c^(1/2.2). Negative input is black.
double reference_tonemap(double c, double exposure, bool filmic) {
  double x = std::max(c, 0.0) * std::pow(2.0, exposure);
  if (filmic) x = (0.9 * x * x + 0.02 * x) / (0.87 * x * x + 0.35 * x + 0.14);
  return std::pow(std::clamp(x, 0.0, 1.0), 1.0 / 2.2);
}

// The GLSL constants are float literals in both builds (0.9f, 1.0f / 2.2f, ...): each is off
// by up to 2^-24 relative, and the curve is at most linearly sensitive to each of its five
// coefficients, the gamma by |ln x| * 2^-24 (|ln x| <= 14 here). Together below 1e-6 relative.
constexpr double kTonemapTol = 1e-6;

TYPED_TEST(ShaderTonemap, MatchesTheDesignFormula) {
  using L = TypeParam;
  using R = typename L::Real;
  const double values[] = {-1.0, -0.0, 0.0, 1e-4, 1e-3, 0.01, 0.05, 0.18, 0.5,
                           1.0,  2.0,  4.0, 10.0, 100.0, 1e4};
  for (int mode : {L::kFilmic, L::kLinear}) {
    for (double exposure : {-2.0, 0.0, 3.0}) {
      for (double c : values) {
        double expected = reference_tonemap(c, exposure, mode == L::kFilmic);
        double got = double(L::tonemap_channel(R(c), R(exposure), mode));
        EXPECT_NEAR(got, expected, kTonemapTol * std::max(expected, 1e-3))
            << (mode == L::kFilmic ? "filmic" : "linear") << " exposure " << exposure << " c " << c;
      }
    }
  }
  // Anchors: linear 1 stays 1 and clamps above; +3 stops of 1/8 is 1; black stays black.
  EXPECT_NEAR(double(L::tonemap_channel(R(1), R(0), L::kLinear)), 1.0, 4 * L::kEps);
  EXPECT_NEAR(double(L::tonemap_channel(R(5), R(0), L::kLinear)), 1.0, 4 * L::kEps);
  EXPECT_NEAR(double(L::tonemap_channel(R(0.125), R(3), L::kLinear)), 1.0, 4 * L::kEps);
  EXPECT_EQ(L::tonemap_channel(R(0), R(3), L::kFilmic), R(0));
  EXPECT_EQ(L::tonemap_channel(R(-2), R(3), L::kLinear), R(0));
  // The filmic curve tends to 0.9 / 0.87 > 1, so bright values clamp to exactly 1.
  EXPECT_EQ(L::tonemap_channel(R(1e4), R(0), L::kFilmic), R(1));
}

TYPED_TEST(ShaderTonemap, IsPerChannelAndMonotonic) {
  using L = TypeParam;
  using R = typename L::Real;
  for (int mode : {L::kFilmic, L::kLinear}) {
    typename L::vec3 rgb = L::tonemap(L::v3(0.1, 0.7, 3.0), R(-2), mode);
    EXPECT_EQ(rgb.x, L::tonemap_channel(R(0.1), R(-2), mode));
    EXPECT_EQ(rgb.y, L::tonemap_channel(R(0.7), R(-2), mode));
    EXPECT_EQ(rgb.z, L::tonemap_channel(R(3.0), R(-2), mode));
    // The curve's derivative has only positive coefficients (0.2976 c^2 + 0.252 c + 0.0028
    // over the squared denominator): the transform never decreases, up to rounding.
    double previous = 0;
    for (int i = 0; i <= 4000; ++i) {
      double c = std::pow(10.0, -4.0 + 7.0 * i / 4000.0);
      double v = double(L::tonemap_channel(R(c), R(0), mode));
      ASSERT_GE(v, previous - 4 * L::kEps) << "c = " << c;
      previous = v;
    }
  }
}

// Very bright values saturate to white, never to black: every value from 12 (where the filmic
// curve passes 1) up to the largest finite one and +inf, at exposures up to 127 stops (where
// c * exp2(exposure) overflows to +inf), and black stays black at any exposure. (c^2 in the
// curve overflowed from c = 2^64 in float: inf / inf is NaN, shown black.)
TYPED_TEST(ShaderTonemap, BrightValuesSaturateToWhite) {
  using L = TypeParam;
  using R = typename L::Real;
  const R max = std::numeric_limits<R>::max(), inf = std::numeric_limits<R>::infinity();
  std::vector<R> bright;
  for (R c = R(12); c < max / R(1.25); c *= R(1.25)) bright.push_back(c);
  for (R c : {max / R(2), std::nextafter(max, R(0)), max, inf}) bright.push_back(c);
  for (int mode : {L::kFilmic, L::kLinear}) {
    for (R exposure : {R(0), R(1), R(66), R(100), R(127), R(200)}) {
      for (R c : bright)
        ASSERT_EQ(L::tonemap_channel(c, exposure, mode), R(1))
            << (mode == L::kFilmic ? "filmic" : "linear") << " exposure " << double(exposure)
            << " c " << double(c);
      EXPECT_EQ(L::tonemap_channel(R(0), exposure, mode), R(0)) << double(exposure);
      EXPECT_EQ(L::tonemap_channel(R(-1), exposure, mode), R(0)) << double(exposure);
    }
    // A dim value at 100 stops is far above white.
    EXPECT_EQ(L::tonemap_channel(R(1e-3), R(100), mode), R(1));
  }
}

TYPED_TEST(ShaderRng, UnitFloatIsInHalfOpenRange) {
  using L = TypeParam;
  using R = typename L::Real;
  EXPECT_EQ(L::rng_to_unit_float(0u), R(0));
  EXPECT_EQ(L::rng_to_unit_float(255u), R(0));
  EXPECT_EQ(L::rng_to_unit_float(256u), R(0x1.0p-24));
  EXPECT_LT(L::rng_to_unit_float(0xffffffffu), R(1));
  EXPECT_EQ(L::rng_to_unit_float(0xffffffffu), R(1.0 - 0x1.0p-24));
  std::uint32_t state = 12345u;
  for (int i = 0; i < 100000; ++i) {
    state = L::rng_advance(state);
    R x = L::rng_to_unit_float(state);
    ASSERT_GE(x, R(0));
    ASSERT_LT(x, R(1));
  }
}

// Streams of neighbouring pixels, consecutive samples and seeds, and consecutive numbers of one
// stream, over N = 1e5 pixels: each set of first numbers has mean 1/2 and variance 1/12 within
// 4 standard errors (sqrt(1/12 / N) for the mean, sqrt((1/80 - 1/144) / N) for the variance of a
// uniform variable), and each pair of sets has a correlation coefficient within 4 / sqrt(N)
// of 0 (its standard error for independent variables).
TYPED_TEST(ShaderRng, NeighbouringStreamsAreUncorrelated) {
  using L = TypeParam;
  const int w = 400, h = 250, n = w * h;
  enum { kBase, kRight, kDown, kNextSample, kNextSeed, kSecondDraw, kCount };
  const char* names[kCount] = {"base", "pixel x + 1", "pixel y + 1", "sample + 1", "seed + 1",
                               "second draw"};
  std::vector<std::vector<double>> v(kCount, std::vector<double>(n));
  const std::uint32_t sample = 7, seed = 3;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      int i = y * w + x;
      std::uint32_t base = L::rng_seed(x, y, sample, seed);
      v[kBase][i] = double(L::rng_to_unit_float(base));
      v[kRight][i] = double(L::rng_to_unit_float(L::rng_seed(x + 1, y, sample, seed)));
      v[kDown][i] = double(L::rng_to_unit_float(L::rng_seed(x, y + 1, sample, seed)));
      v[kNextSample][i] = double(L::rng_to_unit_float(L::rng_seed(x, y, sample + 1, seed)));
      v[kNextSeed][i] = double(L::rng_to_unit_float(L::rng_seed(x, y, sample, seed + 1)));
      v[kSecondDraw][i] = double(L::rng_to_unit_float(L::rng_advance(base)));
    }
  }
  auto mean_of = [&](const std::vector<double>& a) {
    double s = 0;
    for (double x : a) s += x;
    return s / n;
  };
  const double se_mean = std::sqrt(1.0 / 12.0 / n);
  const double se_var = std::sqrt((1.0 / 80.0 - 1.0 / 144.0) / n);
  for (int k = 0; k < kCount; ++k) {
    double m = mean_of(v[k]), var = 0;
    for (double x : v[k]) var += (x - m) * (x - m);
    var /= n - 1;
    EXPECT_NEAR(m, 0.5, 4 * se_mean) << names[k];
    EXPECT_NEAR(var, 1.0 / 12.0, 4 * se_var) << names[k];
  }
  const double mb = mean_of(v[kBase]);
  for (int k = 1; k < kCount; ++k) {
    double mk = mean_of(v[k]), sxy = 0, sxx = 0, syy = 0;
    for (int i = 0; i < n; ++i) {
      sxy += (v[kBase][i] - mb) * (v[k][i] - mk);
      sxx += (v[kBase][i] - mb) * (v[kBase][i] - mb);
      syy += (v[k][i] - mk) * (v[k][i] - mk);
    }
    EXPECT_NEAR(sxy / std::sqrt(sxx * syy), 0.0, 4.0 / std::sqrt(double(n))) << names[k];
  }
}

}  // namespace
}  // namespace glint::shader_test
