// Visible-normal sampling of GGX (shaders/lib/sampling.glsl, sample_ggx_visible_normal; Heitz
// 2018, Dupuy and Benyoub 2023) in float and double: sampled normals follow
// D_wo(h) = G1(wo) max(0, wo.h) D(h) / (n.wo) (chi-square), the sampler stays finite and on the
// upper hemisphere at grazing wo and extreme random numbers, and the sample weight f cos / pdf
// of a rough metal has no more variance than with the old D(h) (n.h) sampler.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/glm.hpp>

#include "ggx_reference.h"
#include "shader_test_util.h"

namespace glint::shader_test {
namespace {

using glm::dvec2;
using glm::dvec3;
constexpr double kPi = std::numbers::pi;

template <class L>
class ShaderVndf : public ::testing::Test {};
TYPED_TEST_SUITE(ShaderVndf, Precisions, PrecisionName);

// D_wo(h) from the double build's D and G1 (tested in shader_sampling_test.cpp), written out
// here rather than taken from ggx_visible_normal_pdf; wo and h local (normal +z).
double reference_dwo(double alpha, dvec3 wo, dvec3 h) {
  double cos_oh = glm::dot(wo, h);
  if (cos_oh <= 0) return 0;
  return DoubleLib::smith_g1(alpha, wo.z) * cos_oh * DoubleLib::ggx_distribution(alpha, h.z) / wo.z;
}

// w = atan(tan(theta) / alpha) * 2 / pi in [0,1] spreads the mass of D over [0,1] for any
// alpha, so that equal w bins all get samples.
double w_of_theta(double theta, double alpha) { return std::atan(std::tan(theta) / alpha) * 2 / kPi; }

// 32 bins in w times 16 azimuth bins; expected counts from adaptive 2D quadrature of
// D_wo(h) sin(theta) dtheta/dw over each bin (tolerance 1e-7, split at the azimuth of wo,
// where the lobe leans); 1e5 samples per case; cells below 5 expected pooled; significance
// kChiSquareAlpha. The total is 1 to 1e-5 (quadrature error at the kink wo.h = 0; n 1e-5 is 1
// sample in all): D_wo is normalised for Smith's G1.
// Also at the glossy coat's smallest alpha (0.03^2) and at grazing wo (n.wo = 0.02).
TYPED_TEST(ShaderVndf, VisibleNormalsFollowDwo) {
  using L = TypeParam;
  using R = typename L::Real;
  const int nw = 32, nphi = 16, n = 100000;
  const double phi_o = 1.0;
  Uniform u(51);
  for (double alpha : {0.05, 0.3, 0.8, 0.0009}) {
    for (double cos_o : {1.0, 0.7, 0.2, 0.02}) {
      SCOPED_TRACE("alpha " + std::to_string(alpha) + ", n.wo " + std::to_string(cos_o));
      double sin_o = std::sqrt(1 - cos_o * cos_o);
      typename L::vec3 wo = L::v3(sin_o * std::cos(phi_o), sin_o * std::sin(phi_o), cos_o);
      dvec3 wo_d = glm::normalize(to_d(wo));  // the reference at the rounded input
      // Integrated over (w, phi), not (theta, phi): at small alpha the last w bin spans
      // theta from 1 to 90 degrees, and at grazing wo its mass sits in a corner (wo.h > 0)
      // that a rule in theta steps over.
      Quadrature2d quadrature(
          [&](double w, double phi) {
            double t = std::tan(0.5 * kPi * w);
            double theta = std::atan(alpha * t);
            double dtheta_dw = alpha * 0.5 * kPi * (1 + t * t) / (1 + alpha * alpha * t * t);
            dvec3 h(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
            return reference_dwo(alpha, wo_d, h) * std::sin(theta) * dtheta_dw;
          },
          1e-7);
      std::vector<double> observed(nw * nphi, 0.0), expected(nw * nphi);
      double total = 0;
      for (int k = 0; k < nw; ++k) {
        for (int j = 0; j < nphi; ++j) {
          double p = quadrature.integrate(double(k) / nw, double(k + 1) / nw, 2 * kPi * j / nphi,
                                          2 * kPi * (j + 1) / nphi, {}, {phi_o});
          expected[k * nphi + j] = n * p;
          total += p;
        }
      }
      EXPECT_NEAR(total, 1.0, 1e-5);
      for (int i = 0; i < n; ++i) {
        dvec2 r = u.vec2();
        typename L::vec3 hl = L::sample_ggx_visible_normal(R(alpha), wo, L::v2(r.x, r.y));
        dvec3 h = to_d(hl);
        ASSERT_NEAR(glm::length(h), 1.0, 8 * L::kEps);
        ASSERT_GE(h.z, 0.0);
        if constexpr (std::is_same_v<R, double>) {
          // The library's density is the reference's (same formula, G1 / cos in one piece).
          ASSERT_TRUE(near_rel(L::ggx_visible_normal_pdf(alpha, wo, hl), reference_dwo(alpha, wo_d, h), 1e-12));
        }
        // atan2, not acos(h.z): near the pole a float h.z resolves theta only to ~3e-4.
        double theta = std::atan2(std::sqrt(h.x * h.x + h.y * h.y), h.z);
        int wi = std::min(nw - 1, int(w_of_theta(theta, alpha) * nw));
        double phi = std::atan2(h.y, h.x);
        if (phi < 0) phi += 2 * kPi;
        int pj = std::min(nphi - 1, int(phi / (2 * kPi) * nphi));
        observed[wi * nphi + pj] += 1;
      }
      ChiSquareResult res = chi_square_test(observed, expected);
      EXPECT_TRUE(res.problem.empty()) << res.describe();
      EXPECT_GE(res.p_value, kChiSquareAlpha) << res.describe();
    }
  }
}

// Finite, unit and on the upper hemisphere for every alpha the materials use, wo from normal
// to exactly grazing (and a rounding below it), and the extreme random numbers 0 and 1 - 2^-24.
TYPED_TEST(ShaderVndf, VisibleNormalSamplerIsFiniteAtTheEdges) {
  using L = TypeParam;
  using R = typename L::Real;
  const double top = 1.0 - 0x1.0p-24;
  const std::vector<double> us = {0.0, 0x1.0p-24, 0.25, 0.5, 0.75, top};
  for (double alpha : {0.0009, 0.01, 0.3, 1.0}) {
    for (double cos_o : {1.0, 0.5, 1e-3, 1e-6, 0.0, -1e-7}) {
      for (double phi_o : {0.0, 1.0, kPi}) {
        double sin_o = std::sqrt(1 - cos_o * cos_o);
        typename L::vec3 wo = L::v3(sin_o * std::cos(phi_o), sin_o * std::sin(phi_o), cos_o);
        for (double a : us) {
          for (double b : us) {
            dvec3 h = to_d(L::sample_ggx_visible_normal(R(alpha), wo, L::v2(a, b)));
            ASSERT_TRUE(std::isfinite(h.x) && std::isfinite(h.y) && std::isfinite(h.z))
                << alpha << " " << cos_o << " " << a << " " << b;
            ASSERT_NEAR(glm::length(h), 1.0, 8 * L::kEps);
            ASSERT_GE(h.z, 0.0);
          }
        }
      }
    }
  }
}

struct Moments {
  double mean = 0, var = 0, var_se = 0;
};
// Mean, variance and the standard error of the variance estimate, sqrt((m4 - var^2) / N).
Moments moments(const std::vector<double>& w) {
  Moments m;
  double n = double(w.size());
  for (double x : w) m.mean += x / n;
  double m4 = 0;
  for (double x : w) {
    double d = (x - m.mean) * (x - m.mean);
    m.var += d / n;
    m4 += d * d / n;
  }
  m.var_se = std::sqrt(std::max(0.0, m4 - m.var * m.var) / n);
  return m;
}

// The sample weight f cos / pdf of a white rough metal (invalid samples weigh 0), 2e5 samples
// per sampler at wo 0, 60, 80 and 89 degrees from the normal: sample_bsdf (visible normals,
// weight F G1(wi)) against the old sampler of D(h) n.h (ggx_reference.h) with its pdf
// D (n.h) / (4 |wo.h|). The new variance must not exceed the old by more than 4 standard
// errors of the difference. Both curves are printed.
TYPED_TEST(ShaderVndf, SampleWeightVarianceIsNotLargerThanWithDCosSampling) {
  using L = TypeParam;
  using R = typename L::Real;
  using V = typename L::vec3;
  const int n = 200000;
  const V nl = L::v3(0, 0, 1);
  Uniform u(52);
  for (double roughness : {0.2, 0.5}) {
    const double alpha = roughness * roughness;
    typename L::SurfaceMaterial m{L::kReflective, L::v3(1, 1, 1), R(roughness), R(1.5)};
    for (double deg : {0.0, 60.0, 80.0, 89.0}) {
      double t = deg * kPi / 180;
      V wo = L::v3(std::sin(t), 0.0, std::cos(t));
      std::vector<double> w_new(n), w_old(n);
      for (int i = 0; i < n; ++i) {
        dvec2 r = u.vec2();
        typename L::BsdfSample s = L::sample_bsdf(m, nl, wo, R(0.5), L::v2(r.x, r.y));
        w_new[i] = s.valid ? double(s.weight.x) : 0.0;
        V h = L::v3(walter_ggx_normal(alpha, u.vec2()));
        V wi = glm::reflect(-wo, h);
        double w = 0;
        if (wi.z > R(0)) {
          R pdf_old = L::ggx_distribution(R(alpha), h.z) * h.z / (R(4) * glm::abs(glm::dot(wo, h)));
          if (pdf_old > R(0)) w = double(L::eval_bsdf(m, nl, wo, wi).x / pdf_old);
        }
        w_old[i] = w;
      }
      Moments mn = moments(w_new), mo = moments(w_old);
      std::printf("[ vndf %s ] roughness %.1f wo %2.0f deg: D-cos sampler mean %.5f var %.5g (+- %.2g); "
                  "visible normals mean %.5f var %.5g (+- %.2g)\n",
                  L::kName, roughness, deg, mo.mean, mo.var, mo.var_se, mn.mean, mn.var, mn.var_se);
      EXPECT_LE(mn.var, mo.var + 4 * std::sqrt(mn.var_se * mn.var_se + mo.var_se * mo.var_se))
          << "roughness " << roughness << " at " << deg << " degrees";
    }
  }
}

}  // namespace
}  // namespace glint::shader_test
