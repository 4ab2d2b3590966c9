// Environment importance sampling: the tables of renderer/environment_distribution.h and the
// sampler and pdf of shaders/lib/environment_sampling.glsl (float and double builds reading the
// same float tables): table invariants, the bilinear support, samples against the pdf
// (chi-square per texel), normalisation over the sphere, rotation, and a 4096 x 2048 map with a
// 1e6 sun whose faint texels keep their probability.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/environment_distribution.h"
#include "shader_test_util.h"

namespace glint::shader_test {
namespace {

using glm::dvec2;
using glm::dvec3;
constexpr double kPi = std::numbers::pi;

Image make_image(int w, int h, const std::function<glm::vec3(int, int)>& f) {
  Image im;
  im.width = w;
  im.height = h;
  im.pixels.assign(static_cast<size_t>(w) * h * 4, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      glm::vec3 c = f(x, y);
      float* p = im.at(x, y);
      p[0] = c.x, p[1] = c.y, p[2] = c.z;
    }
  return im;
}

// Points the shader library's table accessors at d for the scope.
struct BindTables {
  explicit BindTables(const EnvironmentDistribution& d) {
    gpu::environment_tables = {d.width, d.height, d.marginal_cdf.data(), d.conditional_cdf.data()};
  }
  ~BindTables() { gpu::environment_tables = {}; }
};

struct NamedMap {
  const char* name;
  Image image;
};

std::vector<NamedMap> small_maps() {
  return {
      {"gradient", make_image(32, 16, [](int x, int y) { return glm::vec3(0.1f + x, 0.5f * y + 1, 2.0f); })},
      {"sun", make_image(32, 16, [](int x, int y) { return x == 9 && y == 4 ? glm::vec3(1e4f) : glm::vec3(0.0f); })},
      {"black", make_image(32, 16, [](int, int) { return glm::vec3(0.0f); })},
  };
}

dvec3 rotate_y(dvec3 d, double r) {  // +r about +Y, as the sampler's local-to-world
  double c = std::cos(r), s = std::sin(r);
  return {c * d.x + s * d.z, d.y, -s * d.x + c * d.z};
}

dvec3 uv_direction(double u, double v) {
  double phi = 2 * kPi * u, theta = kPi * v;
  return {std::cos(phi) * std::sin(theta), std::cos(theta), std::sin(phi) * std::sin(theta)};
}

// ---------------------------------------------------------------------- tables (C++ only)

TEST(EnvironmentLightTables, CdfsStartAtZeroEndAtOneAndAreMonotone) {
  std::vector<NamedMap> maps = small_maps();
  maps.push_back({"nan and negative", make_image(8, 4, [](int x, int y) {
                    if (x == 2 && y == 1) return glm::vec3(std::nanf(""), 1.0f, 1.0f);
                    if (x == 3 && y == 0) return glm::vec3(-3.0f, -1.0f, -2.0f);
                    return glm::vec3(x == 6 && y == 3 ? 1.0f : 0.0f);
                  })});
  maps.push_back({"infinite", make_image(8, 4, [](int x, int) {
                    return glm::vec3(x == 1 ? INFINITY : 0.0f, 0.0f, 0.0f);
                  })});
  for (const NamedMap& m : maps) {
    EnvironmentDistribution d = build_environment_distribution(m.image);
    ASSERT_EQ(d.marginal_cdf.size(), size_t(d.height + 1));
    EXPECT_EQ(d.marginal_cdf.front(), 0.0f) << m.name;
    EXPECT_EQ(d.marginal_cdf.back(), 1.0f) << m.name;
    for (int i = 0; i < d.height; ++i) EXPECT_LE(d.marginal_cdf[i], d.marginal_cdf[i + 1]) << m.name;
    for (int y = 0; y < d.height; ++y) {
      EXPECT_EQ(d.conditional(y, 0), 0.0f);
      EXPECT_EQ(d.conditional(y, d.width), 1.0f);
      for (int i = 0; i < d.width; ++i) ASSERT_LE(d.conditional(y, i), d.conditional(y, i + 1)) << m.name;
    }
    PackedEnvironmentDistribution p = pack_environment_distribution(d);
    ASSERT_EQ(p.data.size(), size_t(d.height + 1 + d.height * (d.width + 1)));
    EXPECT_EQ(p.data[d.height + 1 + 2 * (d.width + 1) + 3], d.conditional(2, 3));
  }
  // Non-finite and negative texels weigh 0: the only light is the texel at (6, 3).
  std::vector<double> w = environment_texel_weights(maps[3].image);
  EXPECT_GT(w[3 * 8 + 6], 0.0);
  EXPECT_EQ(w[1 * 8 + 2], 0.0);
  EXPECT_EQ(w[0 * 8 + 3], 0.0);
  // Only an infinite texel: nothing finite and positive, so the uniform fallback.
  std::vector<double> wi = environment_texel_weights(maps[4].image);
  EXPECT_EQ(wi[0], wi[5]);
  EXPECT_GT(wi[0], 0.0);
}

// A lone texel's weight is the mean of its bilinear footprint over each texel: 9/16 on itself,
// 3/32 on its four edge neighbours, 1/64 on the corners (times sin theta of the row); u wraps
// (texel 0's left neighbour is the last column) and v clamps (row 0 also stands in for the
// row above it).
TEST(EnvironmentLightTables, WeightsFollowTheBilinearFootprint) {
  const int w = 16, h = 8;
  auto sin_row = [&](int y) { return std::sin(kPi * (y + 0.5) / h); };
  Image im = make_image(w, h, [](int x, int y) { return glm::vec3(x == 0 && y == 3 ? 1.0f : 0.0f); });
  std::vector<double> wt = environment_texel_weights(im);
  const double k[3] = {1.0 / 8, 3.0 / 4, 1.0 / 8};
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      int x = (dx + w) % w, y = 3 + dy;
      EXPECT_DOUBLE_EQ(wt[y * w + x], k[dx + 1] * k[dy + 1] * sin_row(y)) << dx << " " << dy;
    }
  double sum = 0;
  for (double v : wt) sum += v;
  EXPECT_NEAR(sum, sin_row(2) / 8 + sin_row(3) * 3 / 4 + sin_row(4) / 8, 1e-15);
  Image top = make_image(w, h, [](int x, int y) { return glm::vec3(x == 5 && y == 0 ? 1.0f : 0.0f); });
  std::vector<double> wtop = environment_texel_weights(top);
  EXPECT_DOUBLE_EQ(wtop[5], 0.875 * 0.75 * sin_row(0));
}

// Wherever the GPU's bilinear lookup (repeat in u, clamp to edge in v) is > 0, the pdf is > 0:
// random directions and directions packed around a lone bright texel.
TEST(EnvironmentLightTables, PdfIsPositiveWhereTheFilteredLookupIs) {
  const int w = 32, h = 16;
  for (int sy : {0, 7, 15}) {
    Image im = make_image(w, h, [&](int x, int y) { return glm::vec3(x == 31 && y == sy ? 5.0f : 0.0f); });
    EnvironmentDistribution d = build_environment_distribution(im);
    BindTables bind(d);
    auto lookup = [&](double u, double v) {  // luminance of the clamped bilinear filter
      double x = u * w - 0.5, y = v * h - 0.5;
      int x0 = int(std::floor(x)), y0 = int(std::floor(y));
      double fx = x - x0, fy = y - y0, sum = 0;
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
          int xi = ((x0 + i) % w + w) % w, yj = std::clamp(y0 + j, 0, h - 1);
          sum += (i ? fx : 1 - fx) * (j ? fy : 1 - fy) * im.at(xi, yj)[0];
        }
      return sum;
    };
    Uniform u(301);
    int positive = 0;
    for (int i = 0; i < 200000; ++i) {
      // Half uniform over (u, v), half within two texels of the bright one.
      double uu = i % 2 ? u() : (31.5 + 4 * (u() - 0.5)) / w, vv = i % 2 ? u() : (sy + 0.5 + 4 * (u() - 0.5)) / h;
      uu -= std::floor(uu);
      vv = std::clamp(vv, 1e-6, 1 - 1e-6);
      dvec3 dir = uv_direction(uu, vv);
      if (lookup(uu, vv) <= 0) continue;
      ++positive;
      ASSERT_GT(gpu::environment_pdf(glm::vec3(dir), 0.0f), 0.0f) << uu << " " << vv;
    }
    EXPECT_GT(positive, 20000);
  }
}

// ---------------------------------------------------------- sampler and pdf (float, double)

template <class L>
class EnvironmentLight : public ::testing::Test {};
TYPED_TEST_SUITE(EnvironmentLight, Precisions, PrecisionName);

// sample_environment's pdf is environment_pdf of its direction, bit for bit; samples are unit
// and valid; a lone sun's samples all look up inside its bilinear footprint (3 x 3 texels),
// whatever the rotation.
TYPED_TEST(EnvironmentLight, SampledPdfEqualsEvaluatedPdf) {
  using L = TypeParam;
  using R = typename L::Real;
  for (const NamedMap& m : small_maps()) {
    EnvironmentDistribution d = build_environment_distribution(m.image);
    BindTables bind(d);
    Uniform u(302);
    for (double rot : {0.0, 1.3, -4.0}) {
      int invalid = 0;
      for (int i = 0; i < 20000; ++i) {
        auto s = L::sample_environment(L::v2(u(), u()), R(rot));
        if (!s.valid) {
          ++invalid;
          continue;
        }
        ASSERT_NEAR(glm::length(to_d(s.wi)), 1.0, 4 * L::kEps);
        ASSERT_EQ(s.pdf, L::environment_pdf(s.wi, R(rot))) << m.name;
        if (std::string(m.name) == "sun") {
          dvec2 uv = to_d(L::environment_uv(s.wi, R(rot)));
          int x = int(uv.x * 32), y = int(uv.y * 16);
          ASSERT_TRUE(std::abs(x - 9) <= 1 && std::abs(y - 4) <= 1) << x << " " << y;
        }
      }
      // Invalid only where rounding moves a direction into a texel of probability 0.
      EXPECT_LE(invalid, 20) << m.name;
    }
  }
}

// Per-texel chi-square: 2e5 samples binned by the texel environment_uv gives their direction;
// the expected count of a texel integrates environment_pdf over it (d omega = 2 pi^2 sin(theta)
// du dv, 4 x 4 Gauss points, refined once); the integrals must sum to 1 (the pdf is normalised
// over the sphere) to 1e-5 (float rounding of sin(theta) near the poles).
TYPED_TEST(EnvironmentLight, SamplesFollowThePdf) {
  using L = TypeParam;
  using R = typename L::Real;
  const int n = 200000;
  for (const NamedMap& m : small_maps()) {
    EnvironmentDistribution d = build_environment_distribution(m.image);
    BindTables bind(d);
    const int w = d.width, h = d.height;
    for (double rot : {0.0, 2.1}) {
      std::vector<double> observed(w * h, 0.0), expected(w * h, 0.0);
      Uniform u(303);
      for (int i = 0; i < n; ++i) {
        auto s = L::sample_environment(L::v2(u(), u()), R(rot));
        if (!s.valid) continue;
        dvec2 uv = to_d(L::environment_uv(s.wi, R(rot)));
        int x = std::min(w - 1, int(uv.x * w)), y = std::min(h - 1, int(uv.y * h));
        observed[y * w + x] += 1;
      }
      Quadrature2d q(
          [&](double uu, double vv) {
            dvec3 dir = rotate_y(uv_direction(uu, vv), rot);
            return double(L::environment_pdf(L::v3(dir), R(rot))) * 2 * kPi * kPi * std::sin(kPi * vv);
          },
          1e-9, 1);
      double total = 0;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          double p = q.integrate(double(x) / w, double(x + 1) / w, double(y) / h, double(y + 1) / h, {}, {});
          expected[y * w + x] = n * p;
          total += p;
        }
      EXPECT_NEAR(total, 1.0, 1e-5) << m.name;
      ChiSquareResult r = chi_square_test(observed, expected);
      EXPECT_TRUE(r.problem.empty()) << m.name << ": " << r.problem;
      EXPECT_GE(r.p_value, kChiSquareAlpha) << m.name << " rotation " << rot << ": " << r.describe();
    }
  }
}

// Normalisation by an independent route: for uniform directions, E[4 pi pdf] = 1 (4 sigma).
TYPED_TEST(EnvironmentLight, PdfIntegratesToOneOverTheSphere) {
  using L = TypeParam;
  using R = typename L::Real;
  for (const NamedMap& m : small_maps()) {
    if (std::string(m.name) == "sun") continue;  // all mass in 9 texels: variance too large
    EnvironmentDistribution d = build_environment_distribution(m.image);
    BindTables bind(d);
    Uniform u(304);
    const int n = 200000;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
      double v = 4 * kPi * double(L::environment_pdf(L::v3(u.unit_vector()), R(0.7)));
      sum += v;
      sum2 += v * v;
    }
    double mean = sum / n, sigma = std::sqrt((sum2 / n - mean * mean) / (n - 1));
    EXPECT_NEAR(mean, 1.0, 4 * sigma) << m.name;
  }
}

// Rotation: the same random numbers with rotation r give the rotation-0 direction turned by r
// about +Y (8 eps), with the same pdf, and environment_uv(wi, r) is the unrotated uv.
TYPED_TEST(EnvironmentLight, RotationIsConsistentWithEnvironmentUv) {
  using L = TypeParam;
  using R = typename L::Real;
  EnvironmentDistribution d = build_environment_distribution(small_maps()[0].image);
  BindTables bind(d);
  Uniform u(305);
  int pdf_differs = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    auto uv = L::v2(u(), u());
    double rot = 10 * u() - 5;
    auto s0 = L::sample_environment(uv, R(0));
    auto sr = L::sample_environment(uv, R(rot));
    dvec3 expect = rotate_y(to_d(s0.wi), rot);
    ASSERT_NEAR(glm::length(to_d(sr.wi) - expect), 0.0, 8 * L::kEps * std::max(1.0, std::abs(rot)));
    dvec2 a = to_d(L::environment_uv(sr.wi, R(rot))), b = to_d(L::environment_uv(s0.wi, R(0)));
    double du = std::abs(a.x - b.x);
    // (u is ill-conditioned only within ~1e-4 of the poles, which 2e4 samples hardly reach)
    ASSERT_LT(std::min(du, 1 - du) + std::abs(a.y - b.y), 1e-3);
    // Equal unless rounding put one of the two in the neighbouring texel.
    if (!near_rel(double(sr.pdf), double(s0.pdf), 64 * L::kEps)) ++pdf_differs;
  }
  EXPECT_LE(pdf_differs, n / 1000);
}

// ------------------------------------------------------------------------- a 4096 x 2048 map

// A white 4096 x 2048 map (luminance 1) with a 1e6 sun texel. The sun's row has 4096 texels, so
// its faint texels have conditional probabilities near 1.8e-6: a single float prefix sum over
// the 8M texels would lose them (steps of 1e-7 against an ulp of 6e-8), per-row CDFs keep
// them (measured: one float prefix sum over this map gives 675,840 texels probability 0 and a
// median error of 4%). Every texel's realised probability (float CDF differences) is > 0 and within the
// rounding of its two CDF intervals (2^-24 / interval each) of the exact double weight; 1e6
// samples binned into the sun's 3 x 3 block, the rest of its three rows, and 64 bands of rows
// pass chi-square against the double weights. Build and sampling each well under a second.
TEST(EnvironmentLightLargeMap, FaintTexelsBesideASunKeepTheirProbability) {
  const int w = 4096, h = 2048, sx = 1000, sy = 300;
  Image im;
  im.width = w;
  im.height = h;
  im.pixels.assign(static_cast<size_t>(w) * h * 4, 1.0f);
  for (int c = 0; c < 3; ++c) im.at(sx, sy)[c] = 1e6f;
  auto t0 = std::chrono::steady_clock::now();
  std::vector<double> weights = environment_texel_weights(im);
  EnvironmentDistribution d = build_environment_distribution(w, h, weights);
  double build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double total = 0;
  std::vector<double> row_sum(h, 0.0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) row_sum[y] += weights[size_t(y) * w + x];
    total += row_sum[y];
  }
  double worst = 0;
  for (int y = 0; y < h; ++y) {
    double marg = row_sum[y] / total;
    for (int x = 0; x < w; ++x) {
      double wt = weights[size_t(y) * w + x];
      double cond = wt / row_sum[y];
      double pf = d.texel_probability(x, y);
      ASSERT_GT(pf, 0.0) << x << " " << y;
      double bound = 0x1.0p-24 * (1 / cond + 1 / marg) * (1 + 1e-6) + 1e-12;
      double err = std::abs(pf / (marg * cond) - 1);
      worst = std::max(worst, err / bound);
      ASSERT_LE(err, bound) << x << " " << y;
    }
  }
  std::printf("build %.3f s; worst texel error %.3f of its rounding bound; sun row texel p = %.3g\n",
              build_s, worst, d.texel_probability(sx + 5, sy));

  BindTables bind(d);
  const int n = 1000000, bands = 64;
  // cells: 0-8 the sun's block, 9 the rest of rows sy-1..sy+1, then the bands (other rows)
  auto cell_of = [&](int x, int y) {
    if (std::abs(y - sy) <= 1) return std::abs(x - sx) <= 1 ? (y - sy + 1) * 3 + (x - sx + 1) : 9;
    return 10 + y * bands / h;
  };
  std::vector<double> observed(10 + bands, 0.0), expected(10 + bands, 0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) expected[cell_of(x, y)] += n * weights[size_t(y) * w + x] / total;
  Uniform u(306);
  t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < n; ++i) {
    gpu::EnvironmentSample s = gpu::sample_environment(glm::vec2(float(u()), float(u())), 0.0f);
    ASSERT_TRUE(s.valid);
    glm::vec2 uv = gpu::environment_uv(s.wi, 0.0f);
    observed[cell_of(std::min(w - 1, int(uv.x * w)), std::min(h - 1, int(uv.y * h)))] += 1;
  }
  double sample_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("1e6 samples %.3f s; sun block share %.4f\n", sample_s,
              [&] { double s = 0; for (int c = 0; c < 9; ++c) s += observed[c]; return s / n; }());
  ChiSquareResult r = chi_square_test(observed, expected);
  EXPECT_GE(r.p_value, kChiSquareAlpha) << r.describe();
}

// environment_peak_share: a uniform sky spreads its power by solid angle; a sun of one texel
// holds nearly all of it.
TEST(EnvironmentPeakShare, SeparatesASunFromAUniformSky) {
  const int w = 128, h = 64;
  std::vector<double> weights(size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) weights[size_t(y) * w + x] = std::sin(std::numbers::pi * (y + 0.5) / h);
  const EnvironmentDistribution uniform = build_environment_distribution(w, h, weights);
  EXPECT_NEAR(environment_peak_share(uniform, 0.001), 0.001, 2e-4);
  EXPECT_NEAR(environment_peak_share(uniform, 0.25), 0.25, 0.01);
  weights[size_t(20) * w + 30] *= 1e5;
  const EnvironmentDistribution sun = build_environment_distribution(w, h, weights);
  EXPECT_GT(environment_peak_share(sun, 0.001), 0.9);
}

}  // namespace
}  // namespace glint::shader_test
