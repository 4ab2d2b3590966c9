// The Owen-scrambled Sobol sampler of shaders/lib/sobol.glsl (Burley 2020) in float and double:
// the first two Sobol dimensions form (0,m,2)-nets before and after scrambling, every
// power-of-two prefix of a pixel's shuffled sequence is stratified, values lie in [0,1),
// dimensions and pixels are decorrelated (chi-square), and integration error against the PCG
// generator of rng.glsl (measured, and asserted lower at N = 1024).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "shader_test_util.h"

namespace glint::shader_test {
namespace {

using glm::dvec2;

template <class L>
class ShaderSobol : public ::testing::Test {};
TYPED_TEST_SUITE(ShaderSobol, Precisions, PrecisionName);

// True when the 2^m points (cells in 32-bit fixed point) form a (0,m,2)-net in base 2: for
// every split m = a + b, each elementary interval of 2^-a by 2^-b holds exactly one point.
bool is_net(const std::vector<std::uint32_t>& xs, const std::vector<std::uint32_t>& ys, int m,
            std::string& why) {
  for (int a = 0; a <= m; ++a) {
    int b = m - a;
    std::vector<int> count(std::size_t(1) << m, 0);
    for (std::size_t i = 0; i < xs.size(); ++i) {
      std::uint32_t cx = a == 0 ? 0 : xs[i] >> (32 - a), cy = b == 0 ? 0 : ys[i] >> (32 - b);
      if (++count[(std::size_t(cx) << b) | cy] > 1) {
        why = "two points in one " + std::to_string(a) + "/" + std::to_string(b) + " interval";
        return false;
      }
    }
  }
  return true;
}

// A value in [0,1) with 24 bits, as 32-bit fixed point (exact: the conversion is x >> 8 / 2^24).
template <class R>
std::uint32_t fixed(R v) { return std::uint32_t(double(v) * 16777216.0) << 8; }

// Unscrambled: the first 2^m points of Sobol dimensions 0 and 1 for m up to 16, and aligned
// blocks further on ((0,2)-sequence: every block [B 2^m, (B+1) 2^m) is a net), which is what
// the index shuffle maps a pixel's prefix to. Dimension 1's first direction numbers are the
// polynomial x + 1's: 0.1, 0.11, 0.101, 0.1111 in binary.
TYPED_TEST(ShaderSobol, UnscrambledPointsAreNets) {
  using L = TypeParam;
  EXPECT_EQ(L::sobol_dimension1(1u), 0x80000000u);
  EXPECT_EQ(L::sobol_dimension1(2u), 0xc0000000u);
  EXPECT_EQ(L::sobol_dimension1(4u), 0xa0000000u);
  EXPECT_EQ(L::sobol_dimension1(8u), 0xf0000000u);
  EXPECT_EQ(L::sobol_dimension0(1u), 0x80000000u);
  for (std::uint32_t block : {0u, 1u, 7u, 12345u}) {
    for (int m = 0; m <= 16; ++m) {
      if (block > 0 && m > 12) continue;
      std::vector<std::uint32_t> xs, ys;
      for (std::uint32_t i = 0; i < (1u << m); ++i) {
        std::uint32_t index = (block << m) + i;
        xs.push_back(L::sobol_dimension0(index));
        ys.push_back(L::sobol_dimension1(index));
      }
      std::string why;
      EXPECT_TRUE(is_net(xs, ys, m, why)) << "block " << block << ", m = " << m << ": " << why;
    }
  }
}

// Sobol dimensions 1 to 3 as the plain sum over the index bits of the direction numbers from
// Bratley and Fox's recurrence (shaders/lib/sobol.glsl gives them); the shader computes
// dimension 1 by the superset xor transform and 2, 3 by branch-free loops. Every index bit is
// checked alone, and 200000 indices from a fixed PCG stream.
std::uint32_t sobol_by_recurrence(std::uint32_t index, int dimension) {
  std::uint32_t v[34] = {0x80000000u, 0xc0000000u, 0x20000000u};
  for (int k = 1; k < 34; ++k) {
    if (dimension == 1) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
    if (dimension == 2 && k >= 2) v[k] = v[k - 1] ^ v[k - 2] ^ (v[k - 2] >> 2);
    if (dimension == 3 && k >= 3) v[k] = v[k - 2] ^ v[k - 3] ^ (v[k - 3] >> 3);
  }
  std::uint32_t result = 0;
  for (int bit = 0; bit < 32; ++bit)
    if ((index >> bit) & 1u) result ^= v[bit];
  return result;
}

TYPED_TEST(ShaderSobol, DimensionsMatchTheDirectionNumberRecurrence) {
  using L = TypeParam;
  std::vector<std::uint32_t> indices = {0u, 0xffffffffu, 0x80000001u, 0x55555555u};
  for (int bit = 0; bit < 32; ++bit) indices.push_back(1u << bit);
  std::uint64_t state = 0x853c49e6748fea9bull;
  for (int i = 0; i < 200000; ++i) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    indices.push_back(std::uint32_t(state >> 32));
  }
  int mismatches = 0;
  for (std::uint32_t index : indices) {
    mismatches += L::sobol_dimension1(index) != sobol_by_recurrence(index, 1);
    mismatches += L::sobol_dimension2(index) != sobol_by_recurrence(index, 2);
    mismatches += L::sobol_dimension3(index) != sobol_by_recurrence(index, 3);
  }
  EXPECT_EQ(mismatches, 0);
}

// Scrambled, through the public API: for several pixel seeds and dimension pairs, the first
// 2^m samples (m up to 14, every power-of-two prefix of a progressive render) are a
// (0,m,2)-net of the 24-bit values, and the 1-D samples have one point in each 2^-m interval.
TYPED_TEST(ShaderSobol, ScrambledPrefixesAreNets) {
  using L = TypeParam;
  for (std::uint32_t pixel : {0u, 1u, 77u, 0xdeadbeefu}) {
    std::uint32_t seed = L::sobol_pixel_seed(pixel, pixel * 3u, 5u);
    for (std::uint32_t pair : {0u, 1u, 9u}) {
      for (int m = 0; m <= 14; ++m) {
        std::vector<std::uint32_t> xs, ys, zs;
        for (std::uint32_t i = 0; i < (1u << m); ++i) {
          auto p = L::sobol_sample_2d(i, seed, pair);
          xs.push_back(fixed(p.x));
          ys.push_back(fixed(p.y));
          zs.push_back(fixed(L::sobol_sample_1d(i, seed, pair)));
        }
        std::string why;
        EXPECT_TRUE(is_net(xs, ys, m, why)) << "pixel " << pixel << " pair " << pair << " m " << m << ": " << why;
        std::vector<int> strata(std::size_t(1) << m, 0);
        for (std::uint32_t z : zs) strata[m == 0 ? 0 : z >> (32 - m)] += 1;
        EXPECT_EQ(*std::max_element(strata.begin(), strata.end()), 1) << "1-D, pixel " << pixel << " m " << m;
      }
    }
  }
}

// The smallest t for which the 2^m points form a (t,m,2)-net in base 2 (every elementary
// interval of area 2^(t-m) holds 2^t points), or -1 for none.
int net_t(const std::vector<std::uint32_t>& xs, const std::vector<std::uint32_t>& ys, int m) {
  for (int t = 0; t <= m; ++t) {
    bool ok = true;
    const int k = m - t;
    for (int a = 0; a <= k && ok; ++a) {
      const int b = k - a;
      std::vector<int> count(std::size_t(1) << k, 0);
      for (std::size_t i = 0; i < xs.size(); ++i) {
        std::uint32_t cx = a == 0 ? 0 : xs[i] >> (32 - a), cy = b == 0 ? 0 : ys[i] >> (32 - b);
        ++count[(std::size_t(cx) << b) | cy];
      }
      for (int c : count) ok = ok && c == (1 << t);
    }
    if (ok) return t;
  }
  return -1;
}

// The t-values of the six 2-D projections of Sobol dimensions 0 to 3 (Joe-Kuo direction
// numbers) for the first 2^m points, m = 1..8, computed from the generator matrices; Owen
// scrambling and the index shuffle keep them (a shuffled prefix is an aligned block, a digital
// shift of the first one). Dimensions 0 and 1 are the (0,2)-sequence; at 16 points (m = 4)
// dimensions 2 and 3 form a (0,4,2)-net as well.
constexpr int kPairT[6][8] = {{0, 0, 0, 0, 0, 0, 0, 0}, {0, 0, 1, 0, 1, 1, 1, 1}, {0, 0, 1, 2, 0, 1, 2, 1},
                              {0, 1, 0, 1, 1, 1, 1, 1}, {0, 1, 0, 1, 2, 0, 1, 2}, {0, 1, 2, 0, 1, 1, 1, 1}};
constexpr int kPairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

// Sobol dimensions 2 and 3: their first direction numbers (dimension 2: m = 1, 3, 3, 9;
// dimension 3: m = 1, 3, 1, 5, from the recurrences), every dimension 1-D stratified for all
// power-of-two prefixes up to 2^16, and the projections' t-values; then the scrambled 4-D
// points of several pixel seeds and groups with the same t-values and 1-D strata.
TYPED_TEST(ShaderSobol, FourDimensionalPointsAreNets) {
  using L = TypeParam;
  EXPECT_EQ(L::sobol_dimension2(1u), 0x80000000u);
  EXPECT_EQ(L::sobol_dimension2(2u), 0xc0000000u);
  EXPECT_EQ(L::sobol_dimension2(4u), 0x60000000u);
  EXPECT_EQ(L::sobol_dimension2(8u), 0x90000000u);
  EXPECT_EQ(L::sobol_dimension3(1u), 0x80000000u);
  EXPECT_EQ(L::sobol_dimension3(2u), 0xc0000000u);
  EXPECT_EQ(L::sobol_dimension3(4u), 0x20000000u);
  EXPECT_EQ(L::sobol_dimension3(8u), 0x50000000u);
  auto dimension = [](int d, std::uint32_t i) {
    return d == 0 ? L::sobol_dimension0(i) : d == 1 ? L::sobol_dimension1(i) : d == 2 ? L::sobol_dimension2(i) : L::sobol_dimension3(i);
  };
  auto one_per_stratum = [](const std::vector<std::uint32_t>& v, int m) {
    std::vector<int> strata(std::size_t(1) << m, 0);
    for (std::uint32_t z : v) strata[m == 0 ? 0 : z >> (32 - m)] += 1;
    return *std::max_element(strata.begin(), strata.end()) == 1;
  };
  for (int m = 0; m <= 16; ++m) {
    for (int d = 2; d < 4; ++d) {
      std::vector<std::uint32_t> v;
      for (std::uint32_t i = 0; i < (1u << m); ++i) v.push_back(dimension(d, i));
      EXPECT_TRUE(one_per_stratum(v, m)) << "dimension " << d << " m " << m;
    }
  }
  for (int m = 1; m <= 8; ++m) {
    for (int p = 0; p < 6; ++p) {
      std::vector<std::uint32_t> xs, ys;
      for (std::uint32_t i = 0; i < (1u << m); ++i) {
        xs.push_back(dimension(kPairs[p][0], i));
        ys.push_back(dimension(kPairs[p][1], i));
      }
      EXPECT_EQ(net_t(xs, ys, m), kPairT[p][m - 1]) << "dimensions " << kPairs[p][0] << "," << kPairs[p][1] << " m " << m;
    }
  }
  for (std::uint32_t pixel : {0u, 1u, 77u, 0xdeadbeefu}) {
    std::uint32_t seed = L::sobol_pixel_seed(pixel, pixel * 3u, 5u);
    for (std::uint32_t group : {0u, 1u, 9u}) {
      for (int m = 1; m <= 8; ++m) {
        std::vector<std::uint32_t> c[4];
        for (std::uint32_t i = 0; i < (1u << m); ++i) {
          auto q = L::sobol_sample_4d(i, seed, group);
          c[0].push_back(fixed(q.x));
          c[1].push_back(fixed(q.y));
          c[2].push_back(fixed(q.z));
          c[3].push_back(fixed(q.w));
        }
        for (int d = 0; d < 4; ++d) EXPECT_TRUE(one_per_stratum(c[d], m)) << "pixel " << pixel << " coordinate " << d << " m " << m;
        for (int p = 0; p < 6; ++p)
          EXPECT_EQ(net_t(c[kPairs[p][0]], c[kPairs[p][1]], m), kPairT[p][m - 1])
              << "pixel " << pixel << " group " << group << " coordinates " << kPairs[p][0] << "," << kPairs[p][1] << " m " << m;
      }
    }
  }
}

// Values in [0,1) and the float and double builds identical (the pipeline is integer up to
// the exact 24-bit conversion), for random and extreme indices, seeds and dimensions.
TYPED_TEST(ShaderSobol, ValuesAreInTheUnitInterval) {
  using L = TypeParam;
  std::mt19937 g(61);
  std::vector<std::uint32_t> edge = {0u, 1u, 2u, 0x7fffffffu, 0x80000000u, 0xfffffffeu, 0xffffffffu};
  double largest = 0;
  for (int k = 0; k < 200000; ++k) {
    std::uint32_t index = k < 343 ? edge[k % 7] : g(), seed = k < 343 ? edge[k / 7 % 7] : g(),
                  dim = k < 343 ? edge[k / 49] : g() % 64;
    auto p = L::sobol_sample_2d(index, seed, dim);
    double q = double(L::sobol_sample_1d(index, seed, dim));
    for (double v : {double(p.x), double(p.y), q}) {
      ASSERT_GE(v, 0.0);
      ASSERT_LT(v, 1.0);
      largest = std::max(largest, v);
    }
    auto pf = FloatLib::sobol_sample_2d(index, seed, dim);
    ASSERT_EQ(double(p.x), double(pf.x));
    ASSERT_EQ(double(p.y), double(pf.y));
  }
  EXPECT_GT(largest, 1.0 - 1e-4);  // the whole interval is reached
}

// Chi-square test of independence of two sample streams: 16 x 16 cells over [0,1)^2, 4096
// pixels times 256 samples (4096 expected per cell), significance kChiSquareAlpha.
// Stratification only lowers the statistic; a correlation between the two streams raises it.
template <class F>
ChiSquareResult joint_uniformity(F pair_of) {
  const int cells = 16, pixels = 4096, samples = 256;
  std::vector<double> observed(cells * cells, 0.0),
      expected(cells * cells, double(pixels) * samples / (cells * cells));
  for (int p = 0; p < pixels; ++p) {
    for (int i = 0; i < samples; ++i) {
      dvec2 v = pair_of(std::uint32_t(p), std::uint32_t(i));
      observed[int(v.x * cells) * cells + int(v.y * cells)] += 1;
    }
  }
  return chi_square_test(observed, expected);
}

// Dimensions 0 and 1 (pair 0) against 2 and 3 (pair 1) of the same pixel and sample; the
// 1-D dimension 0 against pair 0; and pair 0 of two neighbouring pixels at the same index.
TYPED_TEST(ShaderSobol, DimensionsAndPixelsAreDecorrelated) {
  using L = TypeParam;
  auto seed = [](std::uint32_t p) { return L::sobol_pixel_seed(p % 64u, p / 64u, 3u); };
  for (int a = 0; a < 2; ++a) {
    for (int b = 0; b < 2; ++b) {
      ChiSquareResult r = joint_uniformity([&](std::uint32_t p, std::uint32_t i) {
        auto u = L::sobol_sample_2d(i, seed(p), 0u), v = L::sobol_sample_2d(i, seed(p), 1u);
        return dvec2(a ? u.y : u.x, b ? v.y : v.x);
      });
      EXPECT_GE(r.p_value, kChiSquareAlpha) << "dimension " << a << " vs " << 2 + b << ": " << r.describe();
    }
  }
  ChiSquareResult r1 = joint_uniformity([&](std::uint32_t p, std::uint32_t i) {
    return dvec2(L::sobol_sample_1d(i, seed(p), 0u), L::sobol_sample_2d(i, seed(p), 0u).x);
  });
  EXPECT_GE(r1.p_value, kChiSquareAlpha) << "1-D dimension 0 vs pair 0: " << r1.describe();
  ChiSquareResult r2 = joint_uniformity([&](std::uint32_t p, std::uint32_t i) {
    return dvec2(L::sobol_sample_2d(i, seed(p), 0u).x, L::sobol_sample_2d(i, seed(p + 1u), 0u).x);
  });
  EXPECT_GE(r2.p_value, kChiSquareAlpha) << "neighbouring pixels: " << r2.describe();
}

struct ErrorStats {
  double rms = 0, se = 0;  // RMS error over pixels and its standard error
};
// RMS of the errors over pixels; its standard error by the delta method from the sample
// standard deviation of the squared errors: se(rms) = se(mean square) / (2 rms).
ErrorStats rms_of(const std::vector<double>& errors) {
  double n = double(errors.size()), ms = 0, ms2 = 0;
  for (double e : errors) {
    ms += e * e / n;
    ms2 += e * e * e * e / n;
  }
  ErrorStats s;
  s.rms = std::sqrt(ms);
  s.se = std::sqrt(std::max(0.0, ms2 - ms * ms) / n) / (2 * s.rms);
  return s;
}

// Least-squares slope of log(rms) against log(N).
double slope(const std::vector<int>& ns, const std::vector<ErrorStats>& s) {
  double mx = 0, my = 0, sxy = 0, sxx = 0, k = double(ns.size());
  for (std::size_t i = 0; i < ns.size(); ++i) {
    mx += std::log(double(ns[i])) / k;
    my += std::log(s[i].rms) / k;
  }
  for (std::size_t i = 0; i < ns.size(); ++i) {
    double dx = std::log(double(ns[i])) - mx;
    sxx += dx * dx;
    sxy += dx * (std::log(s[i].rms) - my);
  }
  return sxy / sxx;
}

// Integration of a smooth function, exp(x y) (integral Ei(1) - gamma = 1.3179021514544038),
// and of a disc's indicator (centre (0.45, 0.55), radius 0.35, area pi 0.35^2) over [0,1)^2
// with the first N samples of 1024 independent pixels, N = 16, 64, 256, 1024: Sobol pair 0
// against the PCG stream of rng.glsl (rng_seed per pixel and sample, two rng_advance draws,
// as the trace shader uses it). RMS error over the pixels, printed with the fitted slopes. At
// N = 1024 Sobol's RMS error must be lower than PCG's by more than 4 combined standard errors.
TYPED_TEST(ShaderSobol, IntegratesWithLowerErrorThanPcg) {
  using L = TypeParam;
  const int pixels = 1024;
  const std::vector<int> ns = {16, 64, 256, 1024};
  const double smooth_exact = 1.3179021514544038;
  const double disc_exact = std::numbers::pi * 0.35 * 0.35;
  auto smooth = [](dvec2 p) { return std::exp(p.x * p.y); };
  auto disc = [](dvec2 p) {
    double dx = p.x - 0.45, dy = p.y - 0.55;
    return dx * dx + dy * dy < 0.35 * 0.35 ? 1.0 : 0.0;
  };
  // errors[function][sampler][N index][pixel]
  std::vector<double> blank(pixels);
  std::vector<std::vector<std::vector<std::vector<double>>>> errors(
      2, std::vector<std::vector<std::vector<double>>>(2, std::vector<std::vector<double>>(ns.size(), blank)));
  for (int p = 0; p < pixels; ++p) {
    std::uint32_t px = std::uint32_t(p % 32), py = std::uint32_t(p / 32);
    std::uint32_t sobol_seed = L::sobol_pixel_seed(px, py, 0u);
    for (int sampler = 0; sampler < 2; ++sampler) {
      double sum_s = 0, sum_d = 0;
      std::size_t next = 0;
      for (int i = 0; i < ns.back(); ++i) {
        dvec2 u;
        if (sampler == 0) {
          u = to_d(L::sobol_sample_2d(std::uint32_t(i), sobol_seed, 0u));
        } else {
          std::uint32_t s = L::rng_seed(px, py, std::uint32_t(i), 0u);
          s = L::rng_advance(s);
          double x = double(L::rng_to_unit_float(s));
          s = L::rng_advance(s);
          u = dvec2(x, double(L::rng_to_unit_float(s)));
        }
        sum_s += smooth(u);
        sum_d += disc(u);
        if (i + 1 == ns[next]) {
          errors[0][sampler][next][p] = sum_s / ns[next] - smooth_exact;
          errors[1][sampler][next][p] = sum_d / ns[next] - disc_exact;
          ++next;
        }
      }
    }
  }
  const char* names[2] = {"smooth exp(xy)", "disc indicator"};
  for (int f = 0; f < 2; ++f) {
    std::vector<ErrorStats> sobol, pcg;
    for (std::size_t k = 0; k < ns.size(); ++k) {
      sobol.push_back(rms_of(errors[f][0][k]));
      pcg.push_back(rms_of(errors[f][1][k]));
      std::printf("[ sobol %s ] %s N %4d: RMS error Sobol %.3e (+- %.1e), PCG %.3e (+- %.1e)\n",
                  L::kName, names[f], ns[k], sobol.back().rms, sobol.back().se, pcg.back().rms, pcg.back().se);
    }
    std::printf("[ sobol %s ] %s slopes: Sobol %.2f, PCG %.2f\n", L::kName, names[f], slope(ns, sobol), slope(ns, pcg));
    const ErrorStats &s = sobol.back(), &q = pcg.back();
    EXPECT_LT(s.rms + 4 * std::sqrt(s.se * s.se + q.se * q.se), q.rms) << names[f];
  }
}


// Sample moments of a set of estimates.
struct Moments {
  double mean = 0, variance = 0, kurtosis = 0;  // variance with n - 1; kurtosis m4 / m2^2
};
Moments moments_of(const std::vector<double>& v) {
  Moments m;
  const double n = double(v.size());
  for (double x : v) m.mean += x / n;
  double m2 = 0, m4 = 0;
  for (double x : v) {
    const double d = (x - m.mean) * (x - m.mean);
    m2 += d / n;
    m4 += d * d / n;
  }
  m.variance = m2 * n / (n - 1);
  m.kurtosis = m4 / (m2 * m2);
  return m;
}

// Sample correlation of (a[i], b[i]).
double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const Moments ma = moments_of(a), mb = moments_of(b);
  double c = 0;
  for (std::size_t i = 0; i < a.size(); ++i) c += (a[i] - ma.mean) * (b[i] - mb.mean);
  return c / double(a.size() - 1) / std::sqrt(ma.variance * mb.variance);
}

// The integrand of the seed tests, over the kinds of dimensions the trace shader uses: a disc's
// indicator of the 4-D group's first half times a smooth function of its second half, plus a
// step in the 1-D dimension 2 and a product over pair 3 (7 dimensions, discontinuous and smooth
// parts; integral pi r^2 (Ei(1) - gamma) + 0.3 + 0.25).
constexpr double kDiscR = 0.35;
const double kSeedIntegral = std::numbers::pi * kDiscR * kDiscR * 1.3179021514544038 + 0.3 + 0.25;
template <class L>
double seed_test_estimate(std::uint32_t pixel_seed, int n) {
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const auto g = L::sobol_sample_4d(std::uint32_t(i), pixel_seed, 0u);
    const dvec2 a(double(g.x), double(g.y)), b(double(g.z), double(g.w));
    const double c = double(L::sobol_sample_1d(std::uint32_t(i), pixel_seed, 2u));
    const dvec2 d = to_d(L::sobol_sample_2d(std::uint32_t(i), pixel_seed, 3u));
    const double dx = a.x - 0.45, dy = a.y - 0.55;
    sum += (dx * dx + dy * dy < kDiscR * kDiscR ? std::exp(b.x * b.y) : 0.0) + (c < 0.3 ? 1.0 : 0.0) + d.x * d.y;
  }
  return sum / n;
}

// Every seed is its own randomisation of the point set (the seed enters the scramble of every
// dimension through the pixel seed), so the estimates of one pixel under different seeds are
// independent and identically distributed, as those of different pixels under one seed are:
// what error bars from the spread of seeds need. With n = 8192 estimates (N = 16 points each):
// (a) their mean is the integral within 4 standard errors (sd / sqrt(n));
// (b) the sample correlation of estimate pairs, for neighbouring seeds, seeds that differ in
//     the top bit only, and neighbouring pixels under one seed, is 0 within 4 / sqrt(pairs)
//     (under independence sqrt(pairs) r is asymptotically standard normal);
// (c) the variance across seeds equals the variance across pixels: the log of the ratio of the
//     two sample variances is 0 within 4 of its standard deviations, sqrt(sum over both of
//     (2 / (n - 1) + (kurtosis - 3) / n)), the chi-square variance of a sample variance
//     corrected for the estimates' kurtosis;
// and (d) the variance is that of a low-discrepancy estimate: below half the variance of the
// mean of 16 independent uniform points (the PCG sampler's), Var(F) / 16, with Var(F) estimated
// from single points of the same sequences (the disc's edge holds the gain at N = 16 to about
// N^0.5 = 4: scrambled-net variance of an indicator falls as N^-1.5, Owen 1997).
TYPED_TEST(ShaderSobol, SeedsAreIndependentRandomisations) {
  using L = TypeParam;
  const int n = 8192, points = 16;
  const std::uint32_t px = 7, py = 11;
  std::vector<double> by_seed(n), by_top_bit(n), by_pixel(n), neighbour_pixel(n), single(n);
  for (int k = 0; k < n; ++k) {
    const std::uint32_t s = std::uint32_t(k);
    by_seed[k] = seed_test_estimate<L>(L::sobol_pixel_seed(px, py, s), points);
    by_top_bit[k] = seed_test_estimate<L>(L::sobol_pixel_seed(px, py, s ^ 0x80000000u), points);
    by_pixel[k] = seed_test_estimate<L>(L::sobol_pixel_seed(s % 128u, s / 128u, 12345u), points);
    neighbour_pixel[k] = seed_test_estimate<L>(L::sobol_pixel_seed(s % 128u + 1u, s / 128u, 12345u), points);
    single[k] = seed_test_estimate<L>(L::sobol_pixel_seed(px, py, s + 0x40000000u), 1);
  }
  const Moments seeds = moments_of(by_seed), pixels = moments_of(by_pixel), one = moments_of(single);
  std::printf("[ sobol %s ] N = %d: mean over seeds %.6f (exact %.6f, se %.1e), sd over seeds %.4e, "
              "over pixels %.4e, of one point / sqrt(N) %.4e\n",
              L::kName, points, seeds.mean, kSeedIntegral, std::sqrt(seeds.variance / n),
              std::sqrt(seeds.variance), std::sqrt(pixels.variance), std::sqrt(one.variance / points));
  // (a)
  EXPECT_NEAR(seeds.mean, kSeedIntegral, 4 * std::sqrt(seeds.variance / n));
  EXPECT_NEAR(pixels.mean, kSeedIntegral, 4 * std::sqrt(pixels.variance / n));
  EXPECT_NEAR(one.mean, kSeedIntegral, 4 * std::sqrt(one.variance / n));
  // (b)
  std::vector<double> even, odd;
  for (int k = 0; k + 1 < n; k += 2) {
    even.push_back(by_seed[k]);
    odd.push_back(by_seed[k + 1]);
  }
  const double bound_half = 4 / std::sqrt(double(n / 2)), bound = 4 / std::sqrt(double(n));
  EXPECT_LT(std::abs(correlation(even, odd)), bound_half) << "seeds k and k + 1";
  EXPECT_LT(std::abs(correlation(by_seed, by_top_bit)), bound) << "seeds k and k + 2^31";
  EXPECT_LT(std::abs(correlation(by_pixel, neighbour_pixel)), bound) << "pixels x and x + 1";
  // (c)
  const double log_ratio = std::log(seeds.variance / pixels.variance);
  const double sd = std::sqrt((2.0 / (n - 1) + (seeds.kurtosis - 3) / n) + (2.0 / (n - 1) + (pixels.kurtosis - 3) / n));
  EXPECT_LT(std::abs(log_ratio), 4 * sd) << "variance across seeds / across pixels " << std::exp(log_ratio);
  // (d)
  EXPECT_LT(seeds.variance, 0.5 * one.variance / points);
}

}  // namespace
}  // namespace glint::shader_test
