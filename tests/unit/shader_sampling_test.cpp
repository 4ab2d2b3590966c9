// Frames, warps and the GGX distribution of shaders/lib/sampling.glsl, in float and double:
// orthonormal bases, disk and cosine-hemisphere warps against their densities (chi-square),
// and the normalisation of D. The visible-normal sampler: shader_vndf_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include <glm/glm.hpp>

#include "shader_test_util.h"

namespace glint::shader_test {
namespace {

using glm::dvec2;
using glm::dvec3;
constexpr double kPi = std::numbers::pi;

template <class L>
class ShaderSampling : public ::testing::Test {};
TYPED_TEST_SUITE(ShaderSampling, Precisions, PrecisionName);

TYPED_TEST(ShaderSampling, BasisFromNormalIsOrthonormalAndRightHanded) {
  using L = TypeParam;
  using R = typename L::Real;
  std::vector<dvec3> normals = {{0, 0, 1},  {0, 0, -1}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                {0, -1, 0}, {1e-4, 0, -1}, {0, 1e-7, -1}, {1e-20, 1e-20, -1},
                                {1, 1, -1e-6}, {1, -1, 1e-6}, {0.6, 0.0, -0.8}};
  Uniform u(21);
  for (int i = 0; i < 100000; ++i) normals.push_back(u.unit_vector());
  // Columns are computed from unit n in a few operations: unit length and orthogonality to a
  // few eps, 16 eps allowed (n itself is unit only to an eps or so after rounding).
  const double tol = 16 * L::kEps;
  for (dvec3 nd : normals) {
    typename L::vec3 n = L::v3(glm::normalize(nd));
    typename L::mat3 m = L::basis_from_normal(n);
    dvec3 t = to_d(m[0]), b = to_d(m[1]), z = to_d(m[2]);
    ASSERT_EQ(m[2], n);
    ASSERT_NEAR(glm::length(t), 1.0, tol) << nd.x << " " << nd.y << " " << nd.z;
    ASSERT_NEAR(glm::length(b), 1.0, tol) << nd.x << " " << nd.y << " " << nd.z;
    ASSERT_NEAR(glm::dot(t, b), 0.0, tol) << nd.x << " " << nd.y << " " << nd.z;
    ASSERT_NEAR(glm::dot(t, z), 0.0, tol) << nd.x << " " << nd.y << " " << nd.z;
    ASSERT_NEAR(glm::dot(b, z), 0.0, tol) << nd.x << " " << nd.y << " " << nd.z;
    ASSERT_NEAR(glm::dot(glm::cross(t, b), z), 1.0, tol) << "left-handed at " << nd.z;
  }
  // n = (0, 0, -0.0) style inputs: z = -0 takes the s = +1 branch and must still work.
  typename L::mat3 m = L::basis_from_normal(typename L::vec3(R(1), R(0), R(-0.0)));
  EXPECT_NEAR(double(glm::dot(m[0], m[1])), 0.0, tol);
}

TYPED_TEST(ShaderSampling, SampleDiskStaysInsideTheUnitDisk) {
  using L = TypeParam;
  const double one_below = 1.0 - 0x1.0p-24;
  std::vector<double> edge = {0.0, 0x1.0p-24, 0.25, 0.5, 0.75, one_below};
  for (double x : edge) {
    for (double y : edge) {
      dvec2 p = to_d(L::sample_disk(L::v2(x, y)));
      EXPECT_LE(glm::length(p), 1.0 + 4 * L::kEps) << x << " " << y;
      EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y));
    }
  }
  EXPECT_EQ(L::sample_disk(L::v2(0.5, 0.5)), L::v2(0, 0));
  Uniform u(22);
  for (int i = 0; i < 100000; ++i) {
    dvec2 p = to_d(L::sample_disk(L::v2(u(), u())));
    ASSERT_LE(glm::length(p), 1.0 + 4 * L::kEps);
  }
}

// Area-uniform: 10 rings of equal area (edges at sqrt(k / 10)) times 16 sectors, 2e5 samples,
// 1250 expected per cell; chi-square at significance kChiSquareAlpha.
TYPED_TEST(ShaderSampling, SampleDiskIsAreaUniform) {
  using L = TypeParam;
  const int rings = 10, sectors = 16, n = 200000;
  std::vector<double> observed(rings * sectors, 0.0), expected(rings * sectors, double(n) / (rings * sectors));
  Uniform u(23);
  for (int i = 0; i < n; ++i) {
    dvec2 p = to_d(L::sample_disk(L::v2(u(), u())));
    int ring = std::min(rings - 1, int(glm::dot(p, p) * rings));
    double phi = std::atan2(p.y, p.x);
    if (phi < 0) phi += 2 * kPi;
    int sector = std::min(sectors - 1, int(phi / (2 * kPi) * sectors));
    observed[ring * sectors + sector] += 1;
  }
  ChiSquareResult r = chi_square_test(observed, expected);
  EXPECT_GE(r.p_value, kChiSquareAlpha) << r.describe();
}

// pdf cos(theta) / pi: the probability of cos(theta) in [c0, c1] is c1^2 - c0^2, so bins with
// edges sqrt(k / 10) are equally likely; times 16 azimuth bins; 2e5 samples.
TYPED_TEST(ShaderSampling, CosineHemisphereMatchesCosineOverPi) {
  using L = TypeParam;
  const int nc = 10, nphi = 16, n = 200000;
  std::vector<double> observed(nc * nphi, 0.0), expected(nc * nphi, double(n) / (nc * nphi));
  Uniform u(24);
  for (int i = 0; i < n; ++i) {
    dvec3 w = to_d(L::sample_cosine_hemisphere(L::v2(u(), u())));
    ASSERT_NEAR(glm::length(w), 1.0, 8 * L::kEps);
    ASSERT_GE(w.z, 0.0);
    int ci = std::min(nc - 1, int(w.z * w.z * nc));
    double phi = std::atan2(w.y, w.x);
    if (phi < 0) phi += 2 * kPi;
    int pi = std::min(nphi - 1, int(phi / (2 * kPi) * nphi));
    observed[ci * nphi + pi] += 1;
  }
  ChiSquareResult r = chi_square_test(observed, expected);
  EXPECT_GE(r.p_value, kChiSquareAlpha) << r.describe();
}

// The integral of D(h) cos(theta_h) over the hemisphere is 1. Quadrature: composite Simpson
// with 4096 intervals in w (theta = atan(alpha tan(pi w / 2)), which turns the integrand into
// the smooth (pi / 2) sin(pi w) for exact GGX, so the rule's own error is ~1e-13), with D
// evaluated in the precision under test. In float D's argument cos(theta) is itself rounded:
// near the peak 1 - cos^2 ~ alpha^2 carries a relative error of about eps / alpha^2 (5e-5 at
// alpha = 0.05) that averages out over the peak; 1e-4 allows that. In double the bound is
// 1e-9. The glossy coat's smallest alpha (0.03^2) is checked in double only: in float
// eps / alpha^2 is 15%.
TYPED_TEST(ShaderSampling, GgxDistributionIsNormalised) {
  using L = TypeParam;
  using R = typename L::Real;
  const bool is_float = std::is_same_v<R, float>;
  std::vector<double> alphas = {0.05, 0.1, 0.3, 0.8, 1.0};
  if (!is_float) alphas.push_back(0.0009);
  for (double alpha : alphas) {
    auto f = [alpha](double w) {
      if (w >= 1.0) return 0.0;  // theta = pi / 2: cos(theta) = 0
      double t = std::tan(0.5 * kPi * w);
      double theta = std::atan(alpha * t);
      double dtheta_dw = alpha * 0.5 * kPi * (1 + t * t) / (1 + alpha * alpha * t * t);
      R c = R(std::cos(theta));
      return 2 * kPi * double(L::ggx_distribution(R(alpha), c)) * double(c) * std::sin(theta) *
             dtheta_dw;
    };
    const int m = 4096;
    double sum = f(0.0) + f(1.0);
    for (int i = 1; i < m; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(double(i) / m);
    double integral = sum / (3.0 * m);
    EXPECT_NEAR(integral, 1.0, is_float ? 1e-4 : 1e-9) << "alpha = " << alpha;
  }
  // Below the horizon D is zero.
  EXPECT_EQ(L::ggx_distribution(R(0.3), R(-0.5)), R(0));
  EXPECT_EQ(L::ggx_distribution(R(0.3), R(0)), R(0));
}

// Schlick's Fresnel, independently: F0 + (1 - F0)(1 - cos)^5, with F0 = ((ior-1)/(ior+1))^2.
TYPED_TEST(ShaderSampling, SchlickFresnelAndDielectricF0) {
  using L = TypeParam;
  using R = typename L::Real;
  EXPECT_NEAR(double(L::dielectric_f0(R(1.5))), 0.04, 4 * L::kEps);
  EXPECT_NEAR(double(L::dielectric_f0(R(1.0))), 0.0, 4 * L::kEps);
  for (double f0 : {0.0, 0.04, 0.5, 1.0}) {
    for (double c : {1.0, 0.9, 0.5, 0.1, 1e-4, 0.0}) {
      double expected = f0 + (1 - f0) * std::pow(1 - c, 5);
      EXPECT_NEAR(double(L::fresnel_schlick(R(f0), R(c))), expected, 8 * L::kEps);
      EXPECT_NEAR(double(L::fresnel_schlick(L::v3(f0, f0, f0), R(c)).y), expected, 8 * L::kEps);
    }
  }
}

}  // namespace
}  // namespace glint::shader_test
