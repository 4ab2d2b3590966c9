// The refractive material (shaders/lib/dielectric.glsl, docs/DESIGN.md §7) in float and double:
// the exact Fresnel term against Walter et al.'s closed form, Snell's law and total internal
// reflection of the smooth interface, sampling against eval and pdf, sampled directions against
// the pdf (chi-square) for reflection and transmission on both sides of the interface,
// reciprocity with the eta^2 factor, energy conservation, and no NaN or Inf.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <utility>
#include <numbers>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/glm.hpp>

#include "shader_test_util.h"

namespace glint::shader_test {
namespace {

using glm::dvec3;
constexpr double kPi = std::numbers::pi;

template <class L>
class ShaderDielectric : public ::testing::Test {};
TYPED_TEST_SUITE(ShaderDielectric, Precisions, PrecisionName);

// Relative indices eta (far side over wo's side): entering glass, leaving it (1 / 1.5), and a
// material of index below 1 entered from outside.
const double kEtas[] = {1.5, 1.0 / 1.5, 0.8};
const double kRoughnesses[] = {0.1, 0.3, 0.6};
const double kCosWo[] = {1.0, 0.7, 0.3, 0.05};
const double kPhiWo = 1.0;
const dvec3 kNormal = glm::normalize(dvec3(0.3, -0.4, 0.866));

template <class L>
typename L::SurfaceMaterial refractive(double roughness, double eta, dvec3 color = {1, 1, 1}) {
  using R = typename L::Real;
  return typename L::SurfaceMaterial{L::kRefractive, L::v3(color), R(roughness), R(eta)};
}

std::string describe(double roughness, double eta, double cos_o) {
  return "roughness " + std::to_string(roughness) + ", eta " + std::to_string(eta) + ", n.wo " +
         std::to_string(cos_o);
}

// Walter et al. 2007, eq. 22: F = (g - c)^2 / (2 (g + c)^2) (1 + ((c (g + c) - 1) / (c (g - c) +
// 1))^2), g = sqrt(eta^2 - 1 + c^2), and 1 where g is imaginary (total internal reflection).
// Written independently of fresnel_dielectric (which uses the s and p amplitudes).
double walter_fresnel(double c, double eta) {
  double g2 = eta * eta - 1 + c * c;
  if (g2 <= 0) return 1.0;
  double g = std::sqrt(g2);
  double a = (g - c) / (g + c), b = (c * (g + c) - 1) / (c * (g - c) + 1);
  return 0.5 * a * a * (1 + b * b);
}

bool finite(dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The exact Fresnel term: Walter's closed form to a few eps over the whole angle range (both
// sides, several indices), ((eta - 1) / (eta + 1))^2 at normal incidence, 1 at and beyond the
// critical angle, and continuous there (it reaches 1 as the angle does).
TYPED_TEST(ShaderDielectric, FresnelIsTheExactUnpolarisedReflectance) {
  using L = TypeParam;
  using R = typename L::Real;
  for (double eta : {1.5, 1.0 / 1.5, 1.33, 1.0 / 1.33, 2.4, 0.8, 1.0}) {
    SCOPED_TRACE("eta " + std::to_string(eta));
    for (int i = 0; i <= 1000; ++i) {
      double c = i / 1000.0;
      double expected = walter_fresnel(double(R(c)), double(R(eta)));
      double got = double(L::fresnel_dielectric(R(c), R(eta)));
      // Within 1e-3 of the critical angle (g^2 = eta^2 - 1 + c^2 near 0) F has an unbounded
      // slope in c, and the rounding of c decides: checked for continuity below instead.
      double g2 = eta * eta - 1 + c * c;
      if (std::abs(g2) < 1e-3) continue;
      // The closed form's own rounding grows like 1 / c near grazing (its b term): 64 eps
      // absolute covers both for c >= 1e-3.
      ASSERT_NEAR(got, expected, 64 * L::kEps) << "cos " << c;
      ASSERT_GE(got, 0.0);
      ASSERT_LE(got, 1.0);
    }
    double r = (eta - 1) / (eta + 1);
    EXPECT_NEAR(double(L::fresnel_dielectric(R(1), R(eta))), r * r, 8 * L::kEps);
    EXPECT_EQ(L::fresnel_dielectric(R(0), R(eta)), R(1));  // grazing: all reflected
  }
  // The critical angle of leaving glass, cos_c = sqrt(1 - eta^2): total reflection at it and
  // below it; just above it, F is below 1 and approaches 1.
  const double eta = 1.0 / 1.5, cos_c = std::sqrt(1 - eta * eta);
  EXPECT_EQ(L::fresnel_dielectric(R(cos_c * (1 - 4 * L::kEps)), R(eta)), R(1));
  double previous = 0;
  for (double d : {1e-1, 1e-2, 1e-3}) {
    double f = double(L::fresnel_dielectric(R(cos_c + d), R(eta)));
    EXPECT_LT(f, 1.0);
    EXPECT_GT(f, previous);
    previous = f;
  }
  EXPECT_GT(previous, 0.5);
}

// The smooth interface: reflection (the mirror direction, weight 1) with probability F(n.wo),
// otherwise the refracted direction of Snell's law (eta sin(theta_t) = sin(theta_o), on the far
// side, in the plane of wo and n) with weight colour / eta^2. The reflected fraction of 1e5
// samples is within 4.5 binomial standard errors of the exact F. Beyond the critical angle,
// and exactly at it, every sample reflects.
TYPED_TEST(ShaderDielectric, SmoothInterfaceObeysFresnelAndSnell) {
  using L = TypeParam;
  using R = typename L::Real;
  const Frame frame(kNormal);
  const typename L::vec3 n = L::v3(kNormal);
  const dvec3 color(0.9, 0.6, 0.3);
  const int samples = 100000;
  Uniform u(41);
  for (double eta : {1.5, 1.0 / 1.5, 1.33, 2.4, 0.8}) {
    for (double roughness : {0.0, 0.0299}) {
      typename L::SurfaceMaterial m = refractive<L>(roughness, eta, color);
      ASSERT_TRUE(L::is_delta_material(m));
      for (double cos_o : {1.0, 0.9, 0.5, 0.2, 0.05, 1e-3}) {
        SCOPED_TRACE(describe(roughness, eta, cos_o));
        typename L::vec3 wo = L::v3(frame.to_world(cos_o, kPhiWo));
        const double c = double(glm::dot(n, wo));
        const dvec3 mirror = 2.0 * c * to_d(n) - to_d(wo);
        const double f = walter_fresnel(c, double(m.ior));
        int reflected = 0;
        for (int i = 0; i < samples; ++i) {
          typename L::BsdfSample s = L::sample_bsdf(m, n, wo, R(u()), L::v2(u(), u()));
          ASSERT_TRUE(s.valid && s.delta);
          ASSERT_EQ(s.pdf, R(0));
          dvec3 wi = to_d(s.wi);
          ASSERT_NEAR(glm::length(wi), 1.0, 8 * L::kEps);
          if (glm::dot(wi, to_d(n)) > 0) {
            ++reflected;
            ASSERT_LE(glm::length(wi - mirror), 8 * L::kEps);
            ASSERT_EQ(s.weight, L::v3(1, 1, 1));
          } else {
            double sin_o = std::sqrt(std::max(0.0, 1 - c * c));
            double sin_t = glm::length(wi - glm::dot(wi, to_d(n)) * to_d(n));
            // Snell: conditioning of sin from the cosine near normal incidence, ~eps / sin.
            ASSERT_NEAR(eta * sin_t, sin_o, 16 * L::kEps * (1 + 1 / std::max(sin_o, 1e-3)));
            ASSERT_LE(std::abs(glm::dot(wi, glm::cross(to_d(n), to_d(wo)))), 16 * L::kEps);
            ASSERT_LE(glm::dot(wi - glm::dot(wi, to_d(n)) * to_d(n), to_d(wo)), 16 * L::kEps);
            for (int k = 0; k < 3; ++k)
              ASSERT_NEAR(double(s.weight[k]), color[k] / (eta * eta), 8 * L::kEps);
          }
        }
        double se = std::sqrt(f * (1 - f) / samples);
        EXPECT_NEAR(double(reflected) / samples, f, 4.5 * se + 1.0 / samples) << "F " << f;
      }
    }
  }
  // Total internal reflection at and beyond the critical angle of leaving glass.
  for (double eta : {1.0 / 1.5, 1.0 / 2.4}) {
    typename L::SurfaceMaterial m = refractive<L>(0, eta);
    const double cos_c = std::sqrt(1 - eta * eta);
    for (double cos_o : {cos_c, cos_c * (1 - 1e-3), 0.5 * cos_c, 1e-3}) {
      SCOPED_TRACE(describe(0, eta, cos_o));
      typename L::vec3 wo = L::v3(frame.to_world(cos_o, kPhiWo));
      // At exactly cos_c (as rounded), sin^2 t is 1 up to rounding: either total reflection
      // or a grazing refraction with F within rounding of 1; both are valid, finite samples.
      for (double lobe : {0.0, 0.5, 1.0 - 0x1.0p-24}) {
        typename L::BsdfSample s = L::sample_bsdf(m, n, wo, R(lobe), L::v2(0.5, 0.5));
        ASSERT_TRUE(s.valid && s.delta && finite(to_d(s.wi)) && finite(to_d(s.weight)));
        if (cos_o < cos_c) {
          ASSERT_GT(glm::dot(s.wi, n), R(0));
        }
      }
    }
  }
}

// Grazing entry: wo at n.wo = 1e-4 entering glass refracts to just inside the critical angle
// (sin(theta_t) = sin(theta_o) / eta ~ 1 / eta), and most of the light reflects.
TYPED_TEST(ShaderDielectric, GrazingEntryRefractsToTheCriticalAngle) {
  using L = TypeParam;
  using R = typename L::Real;
  const Frame frame(kNormal);
  const typename L::vec3 n = L::v3(kNormal);
  const double eta = 1.5;
  typename L::SurfaceMaterial m = refractive<L>(0, eta);
  for (double cos_o : {1e-2, 1e-3, 1e-4}) {
    typename L::vec3 wo = L::v3(frame.to_world(cos_o, kPhiWo));
    const double c = double(glm::dot(n, wo));
    typename L::BsdfSample s = L::sample_bsdf(m, n, wo, R(1.0 - 0x1.0p-24), L::v2(0.5, 0.5));
    ASSERT_TRUE(s.valid && s.delta);
    ASSERT_LT(glm::dot(s.wi, n), R(0));
    double sin_t = glm::length(to_d(s.wi) - glm::dot(to_d(s.wi), to_d(n)) * to_d(n));
    EXPECT_NEAR(sin_t, std::sqrt(1 - c * c) / eta, 16 * L::kEps);
    EXPECT_GT(double(L::fresnel_dielectric(R(c), R(eta))), 0.9);
  }
}

// For every rough sample: weight = eval / pdf and pdf = pdf_bsdf at the sampled direction to a
// few eps; wi is unit; reflection above, transmission below.
TYPED_TEST(ShaderDielectric, SampleAgreesWithEvalAndPdf) {
  using L = TypeParam;
  using R = typename L::Real;
  const Frame frame(kNormal);
  const typename L::vec3 n = L::v3(kNormal);
  Uniform u(42);
  for (double eta : kEtas)
    for (double roughness : kRoughnesses)
      for (double cos_o : kCosWo) {
        SCOPED_TRACE(describe(roughness, eta, cos_o));
        typename L::SurfaceMaterial m = refractive<L>(roughness, eta, {0.8, 0.6, 0.4});
        ASSERT_FALSE(L::is_delta_material(m));
        typename L::vec3 wo = L::v3(frame.to_world(cos_o, kPhiWo));
        int valid = 0, transmitted = 0;
        for (int i = 0; i < 20000; ++i) {
          typename L::BsdfSample s = L::sample_bsdf(m, n, wo, R(u()), L::v2(u(), u()));
          if (!s.valid) continue;
          ++valid;
          transmitted += glm::dot(s.wi, n) < R(0);
          ASSERT_FALSE(s.delta);
          ASSERT_NEAR(glm::length(to_d(s.wi)), 1.0, 16 * L::kEps);
          double pdf = double(L::pdf_bsdf(m, n, wo, s.wi));
          ASSERT_GT(pdf, 0.0);
          ASSERT_TRUE(near_rel(double(s.pdf), pdf, 4 * L::kEps)) << s.pdf << " vs " << pdf;
          dvec3 expected = to_d(L::eval_bsdf(m, n, wo, s.wi)) / double(s.pdf);
          for (int k = 0; k < 3; ++k)
            ASSERT_TRUE(near_rel(double(s.weight[k]), expected[k], 8 * L::kEps, 1e-30))
                << s.weight[k] << " vs " << expected[k];
        }
        EXPECT_GT(valid, 10000);
        if (eta > 1) {
          EXPECT_GT(transmitted, 0);  // entering: no total internal reflection
        }
      }
}

// Bin probabilities of (cos theta, phi) under pdf_bsdf (double build), by adaptive
// Gauss-Legendre (tolerance 1e-8 per bin), split first at the specular peaks: the mirror
// direction (theta_o, phi_o + pi) and the refracted one (pi - theta_t, phi_o + pi).
std::vector<double> bin_probabilities(const DoubleLib::SurfaceMaterial& m, const Frame& frame,
                                      dvec3 n, dvec3 wo, int n_cos, int n_phi) {
  double cos_o = std::clamp(frame.cos_theta(wo), -1.0, 1.0);
  double theta_o = std::acos(cos_o);
  double sin_t = std::sqrt(1 - cos_o * cos_o) / m.ior;
  std::vector<double> theta_breaks = {theta_o};
  if (sin_t < 1) theta_breaks.push_back(kPi - std::asin(sin_t));
  double phi_peak = std::fmod(frame.phi(wo) + kPi, 2 * kPi);
  Quadrature2d quadrature(
      [&](double theta, double phi) {
        return DoubleLib::pdf_bsdf(m, n, wo, frame.to_world(std::cos(theta), phi)) * std::sin(theta);
      },
      1e-8);
  std::vector<double> probs(n_cos * n_phi);
  for (int i = 0; i < n_cos; ++i) {
    double t0 = std::acos(-1.0 + 2.0 * (i + 1) / n_cos), t1 = std::acos(-1.0 + 2.0 * i / n_cos);
    for (int j = 0; j < n_phi; ++j) {
      double p0 = 2 * kPi * j / n_phi, p1 = 2 * kPi * (j + 1) / n_phi;
      probs[i * n_phi + j] = quadrature.integrate(t0, t1, p0, p1, theta_breaks, {phi_peak});
    }
  }
  return probs;
}

// Chi-square goodness of fit of sampled directions against pdf_bsdf, over 40 cos(theta) bins
// on [-1, 1] (both hemispheres: reflection and transmission) times 32 azimuth bins, 2e5 samples
// per case, cells with an expected count below 5 pooled, significance kChiSquareAlpha; on the
// same run, the pdf's integral over the sphere (quadrature error below 1e-5) equals the valid
// fraction within 4.5 binomial standard errors. One ctest per case and precision.
struct ChiSquareCase {
  double eta, roughness, cos_o;
};

void PrintTo(const ChiSquareCase& c, std::ostream* os) { *os << describe(c.roughness, c.eta, c.cos_o); }

template <class L>
void check_sampled_directions(const ChiSquareCase& c) {
  using R = typename L::Real;
  const int n_cos = 40, n_phi = 32, n = 200000;
  const Frame frame(kNormal);
  const typename L::vec3 nl = L::v3(kNormal);
  Uniform u(43);
  typename L::SurfaceMaterial m = refractive<L>(c.roughness, c.eta);
  typename L::vec3 wo = L::v3(frame.to_world(c.cos_o, kPhiWo));
  DoubleLib::SurfaceMaterial md{L::kRefractive, dvec3(1), double(m.roughness), double(m.ior)};
  std::vector<double> probs = bin_probabilities(md, frame, glm::normalize(to_d(nl)),
                                                glm::normalize(to_d(wo)), n_cos, n_phi);
  std::vector<double> observed(probs.size(), 0.0), expected(probs.size());
  int invalid = 0, transmitted = 0;
  for (int i = 0; i < n; ++i) {
    typename L::BsdfSample s = L::sample_bsdf(m, nl, wo, R(u()), L::v2(u(), u()));
    if (!s.valid) {
      ++invalid;
      continue;
    }
    dvec3 wi = glm::normalize(to_d(s.wi));
    transmitted += frame.cos_theta(wi) < 0;
    observed[sphere_bin(frame, wi, n_cos, n_phi)] += 1;
  }
  double total = 0;
  for (std::size_t k = 0; k < probs.size(); ++k) {
    expected[k] = n * probs[k];
    total += probs[k];
  }
  ChiSquareResult r = chi_square_test(observed, expected);
  EXPECT_TRUE(r.problem.empty()) << r.describe();
  EXPECT_GE(r.p_value, kChiSquareAlpha) << r.describe() << " (" << transmitted << " transmitted)";
  double p_invalid = double(invalid) / n;
  double se = std::sqrt(std::max(p_invalid * (1 - p_invalid), 1.0 / n) / n);
  EXPECT_NEAR(total, 1.0 - p_invalid, 4.5 * se + 1e-5)
      << "integral of the pdf " << total << ", invalid fraction " << p_invalid;
}

class DielectricSampledDirections : public ::testing::TestWithParam<ChiSquareCase> {};
TEST_P(DielectricSampledDirections, FollowThePdfInFloat) { check_sampled_directions<FloatLib>(GetParam()); }
TEST_P(DielectricSampledDirections, FollowThePdfInDouble) { check_sampled_directions<DoubleLib>(GetParam()); }

// Entering glass (eta 1.5), leaving it (1 / 1.5, where total internal reflection sends every
// sample up beyond the critical angle) and entering a material of index below 1 (0.8), each at
// a near-specular, a medium and a broad roughness, from near normal to near grazing incidence.
INSTANTIATE_TEST_SUITE_P(
    Cases, DielectricSampledDirections,
    ::testing::Values(ChiSquareCase{1.5, 0.1, 0.7}, ChiSquareCase{1.0 / 1.5, 0.1, 0.7},
                      ChiSquareCase{0.8, 0.1, 0.3}, ChiSquareCase{1.5, 0.3, 0.5},
                      ChiSquareCase{1.0 / 1.5, 0.3, 0.5}, ChiSquareCase{0.8, 0.3, 0.05},
                      ChiSquareCase{0.8, 0.6, 1.0}, ChiSquareCase{1.5, 0.6, 0.05},
                      ChiSquareCase{1.0 / 1.5, 0.6, 0.3}));

// Reciprocity with the eta^2 factor: the radiance BSDF satisfies f(wo, wi) / eta_o^2 =
// f(wi, wo) / eta_i^2 (Veach 1997, eq. 5.23), i.e. with eval = f |n.wi| and the swapped
// query seen from wi's side (the normal flipped to wi, the relative index 1 / eta for a
// transmission): eval(wo, wi; eta) / |n.wi| * eta^2 = eval(wi, wo; 1 / eta) / |n.wo|, and for a
// reflection (same side, same eta) the plain symmetry. A missing or misplaced eta^2 is off by
// 2.25 at eta 1.5, a wrong Jacobian by more; the tolerances below are far smaller.
struct ReciprocityPair {
  dvec3 wo, wi;
  double eta, eta_swapped, scale;  // scale: eta^2 for a transmission, 1 for a reflection
  bool transmission;
};

// 20000 pairs on the sphere, half of them transmissions, n.wo and |n.wi| in [0.05, 1], with
// pairs whose microfacet lies within 1e-3 of the critical angle dropped (there Fresnel's slope
// is unbounded and either side's rounding decides).
template <class Visit>
void for_each_reciprocity_pair(double eta, Uniform& u, Visit visit) {
  const Frame frame(kNormal);
  for (int i = 0; i < 20000; ++i) {
    ReciprocityPair p;
    double co = 0.05 + 0.95 * u();
    double ci = (i % 2 ? -1.0 : 1.0) * (0.05 + 0.95 * u());
    p.wo = frame.to_world(co, 2 * kPi * u());
    p.wi = frame.to_world(ci, 2 * kPi * u());
    p.transmission = ci < 0;
    p.eta = eta;
    p.eta_swapped = p.transmission ? 1 / eta : eta;
    p.scale = p.transmission ? eta * eta : 1.0;
    dvec3 h = p.transmission ? p.wo + eta * p.wi : p.wo + p.wi;
    h = glm::normalize(glm::dot(h, kNormal) < 0 ? -h : h);
    double cos_oh = glm::dot(p.wo, h);
    double sin2_t = (1 - cos_oh * cos_oh) / (eta * eta);
    if (std::abs(1 - sin2_t) < 1e-3) continue;
    visit(p);
  }
}

// Both sides of the reciprocity relation, f(wo, wi) eta^2 / |n.wi| and f(wi, wo) / |n.wo| (red
// channel: the colour multiplies every channel alike), in library L at inputs already in its
// precision.
template <class L>
std::pair<double, double> reciprocity_sides(const ReciprocityPair& p, double roughness,
                                            typename L::vec3 n, typename L::vec3 wo,
                                            typename L::vec3 wi) {
  using R = typename L::Real;
  typename L::SurfaceMaterial m{L::kRefractive, L::v3(dvec3(0.9, 0.5, 0.2)), R(roughness), R(p.eta)};
  typename L::SurfaceMaterial ms{L::kRefractive, L::v3(dvec3(0.9, 0.5, 0.2)), R(roughness),
                                 R(p.eta_swapped)};
  typename L::vec3 n_swapped = p.transmission ? -n : n;
  double f_oi = double(L::eval_bsdf(m, n, wo, wi).x);
  double f_io = double(L::eval_bsdf(ms, n_swapped, wi, wo).x);
  return {f_oi / std::abs(double(glm::dot(n, wi))) * p.scale,
          f_io / std::abs(double(glm::dot(n, wo)))};
}

// Double: the two sides agree to a relative 1e-9, far above double rounding and far below any
// wrong factor. Values below 1e-4 are compared absolutely (to 1e-13): where one side's
// microfacet is near total internal reflection, its 1 - F is 1 minus a number within rounding
// of 1, so the two sides differ by ~1e-15 absolute however small the value (measured: 1e-13 to
// 1e-6 values differed by 1e-18 to 2e-15).
TEST(ShaderDielectricDouble, ReciprocityWithTheEtaSquaredFactor) {
  using L = DoubleLib;
  Uniform u(44);
  for (double eta : {1.5, 1.0 / 1.5, 0.8})
    for (double roughness : {0.2, 0.5}) {
      SCOPED_TRACE("roughness " + std::to_string(roughness) + " eta " + std::to_string(eta));
      int compared = 0, transmissions = 0;
      for_each_reciprocity_pair(eta, u, [&](const ReciprocityPair& p) {
        auto [a, b] = reciprocity_sides<L>(p, roughness, kNormal, p.wo, p.wi);
        ASSERT_TRUE(std::isfinite(a) && std::isfinite(b) && a >= 0 && b >= 0);
        if (a == 0 && b == 0) return;
        ASSERT_TRUE(near_rel(a, b, 1e-9, 1e-4)) << a << " vs " << b;
        ++compared;
        transmissions += p.transmission;
      });
      EXPECT_GT(compared, 2000);
      EXPECT_GT(transmissions, 500);
    }
}

// Float: each side is compared with its double evaluation at the same float inputs, whose
// reciprocity the double test establishes, and the float error of each side is bounded by its
// forward error: how far the double value moves when the float inputs (n, wo, wi, each
// component) move by a few float ulps, as rounding in the float evaluation moves them (the
// largest change over 8 random perturbations of 2 eps: this measures the conditioning of the
// peaky D, of the half vector's cancellation in a transmission and of Fresnel without a
// hand-derived formula for each), plus the cancellation in 1 - F for a transmission
// (eps F / (1 - F) relative: not an input perturbation) and 16 eps for the rounding of the
// products. Allowed: 4 times that per side, so the two sides agree within the sum. Measured:
// the largest float error is 1.6 times its bound (printed), and an error of 1e-5 relative
// (84 eps) planted in one side fails about 12000 of the 120000 pairs.
TEST(ShaderDielectricFloat, ReciprocityWithinTheRoundingOfItsInputs) {
  using F = FloatLib;
  const double eps = F::kEps;
  Uniform u(44), jitter(47);
  double worst_ratio = 0;  // the largest float error per side over its bound
  for (double eta : {1.5, 1.0 / 1.5, 0.8})
    for (double roughness : {0.2, 0.5}) {
      SCOPED_TRACE("roughness " + std::to_string(roughness) + " eta " + std::to_string(eta));
      int compared = 0, transmissions = 0;
      for_each_reciprocity_pair(eta, u, [&](const ReciprocityPair& p) {
        const glm::vec3 n(kNormal), wo(p.wo), wi(p.wi);
        auto [a, b] = reciprocity_sides<F>(p, roughness, n, wo, wi);
        ASSERT_TRUE(std::isfinite(a) && std::isfinite(b) && a >= 0 && b >= 0);
        // The double value at the float inputs (normalised: a float unit vector is off unit
        // length by an ulp, which would break the exact relation; that ulp is within the
        // perturbations below), and its spread under perturbed inputs.
        const dvec3 nd = glm::normalize(to_d(n)), wod = glm::normalize(to_d(wo)),
                    wid = glm::normalize(to_d(wi));
        auto [ad, bd] = reciprocity_sides<DoubleLib>(p, double(float(roughness)), nd, wod, wid);
        double spread_a = 0, spread_b = 0;
        for (int k = 0; k < 8; ++k) {
          auto perturb = [&](dvec3 d) {
            for (int c = 0; c < 3; ++c) d[c] *= 1 + 2 * eps * (2 * jitter() - 1);
            return d;
          };
          auto [ap, bp] = reciprocity_sides<DoubleLib>(p, double(float(roughness)), perturb(nd),
                                                       perturb(wod), perturb(wid));
          spread_a = std::max(spread_a, std::abs(ap - ad));
          spread_b = std::max(spread_b, std::abs(bp - bd));
        }
        // 1 - F of each side's microfacet, for the cancellation term (0 for a reflection).
        double cancel_a = 0, cancel_b = 0;
        if (p.transmission) {
          dvec3 h = glm::normalize(p.wo + p.eta * p.wi);
          double fa = walter_fresnel(std::abs(glm::dot(p.wo, h)), p.eta);
          double fb = walter_fresnel(std::abs(glm::dot(p.wi, h)), p.eta_swapped);
          cancel_a = fa / std::max(1 - fa, 1e-300);
          cancel_b = fb / std::max(1 - fb, 1e-300);
        }
        double bound_a = spread_a + eps * (16 + 4 * cancel_a) * ad;
        double bound_b = spread_b + eps * (16 + 4 * cancel_b) * bd;
        double err_a = std::abs(a - ad), err_b = std::abs(b - bd);
        if (bound_a > 0) worst_ratio = std::max(worst_ratio, err_a / bound_a);
        if (bound_b > 0) worst_ratio = std::max(worst_ratio, err_b / bound_b);
        ASSERT_LE(err_a, 4 * bound_a + 1e-30) << a << " vs double " << ad;
        ASSERT_LE(err_b, 4 * bound_b + 1e-30) << b << " vs double " << bd;
        ASSERT_TRUE(near_rel(ad, bd, 1e-9, 1e-4)) << ad << " vs " << bd;  // as in double
        ASSERT_LE(std::abs(a - b), 4 * (bound_a + bound_b) + 1e-9 * std::max({ad, bd, 1e-4}))
            << a << " vs " << b;
        if (a == 0 && b == 0) return;
        ++compared;
        transmissions += p.transmission;
      });
      EXPECT_GT(compared, 2000);
      EXPECT_GT(transmissions, 500);
    }
  std::cout << "largest float error over its bound: " << worst_ratio << "\n";
}

// Energy: a clear interface conserves the flux of importance, so the expected weight with the
// transmitted samples' radiance scaling undone (times eta^2) is exactly 1 when smooth (F +
// (1 - F)) and at most 1 when rough (single scattering loses what the microfacets shadow),
// within 4 standard errors of 1e5 samples.
TYPED_TEST(ShaderDielectric, ClearInterfaceConservesEnergy) {
  using L = TypeParam;
  using R = typename L::Real;
  const Frame frame(kNormal);
  const typename L::vec3 nl = L::v3(kNormal);
  const int n = 100000;
  Uniform u(45);
  for (double eta : {1.5, 1.0 / 1.5, 0.8})
    for (double roughness : {0.0, 0.1, 0.3, 0.6, 1.0})
      for (double cos_o : {1.0, 0.7, 0.3, 0.05, 0.01}) {
        SCOPED_TRACE(describe(roughness, eta, cos_o));
        typename L::SurfaceMaterial m = refractive<L>(roughness, eta);
        typename L::vec3 wo = L::v3(frame.to_world(cos_o, kPhiWo));
        double sum = 0, sum2 = 0;
        for (int i = 0; i < n; ++i) {
          typename L::BsdfSample s = L::sample_bsdf(m, nl, wo, R(u()), L::v2(u(), u()));
          double w = 0;
          if (s.valid) {
            w = double(s.weight.x) * (glm::dot(s.wi, nl) < R(0) ? eta * eta : 1.0);
            if (roughness < 0.03) {
              ASSERT_NEAR(w, 1.0, 8 * L::kEps);
            }
          }
          sum += w;
          sum2 += w * w;
        }
        double mean = sum / n;
        double se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
        EXPECT_LE(mean, 1.0 + 4 * se + 8 * L::kEps) << "albedo " << mean << " +- " << se;
      }
}

// No NaN or Inf: roughness 0 to 1 (and around the delta threshold), relative indices from 0.5
// to 3 including 1 and 1 + 1e-4, wo from normal to grazing, random and extreme random numbers;
// eval and pdf for random, grazing, normal and opposite directions (-wo is the degenerate
// transmission of eta 1).
TYPED_TEST(ShaderDielectric, NoNanOrInfAnywhere) {
  using L = TypeParam;
  using R = typename L::Real;
  const Frame frame(kNormal);
  const typename L::vec3 n = L::v3(kNormal);
  const double top = 1.0 - 0x1.0p-24;
  const std::vector<double> extremes = {0.0, 0x1.0p-24, 0.5, top};
  Uniform u(46);
  int checked = 0;
  for (double eta : {0.5, 1.0 / 1.5, 1.0, 1.0001, 1.5, 3.0})
    for (double roughness : {0.0, 0.0299, 0.03, 0.05, 0.2, 0.5, 1.0}) {
      typename L::SurfaceMaterial m = refractive<L>(roughness, eta, {0.9, 0.5, 0.1});
      for (double cos_o : {1.0, 0.5, 0.05, 1e-3, 1e-4}) {
        SCOPED_TRACE(describe(roughness, eta, cos_o));
        typename L::vec3 wo = L::v3(frame.to_world(cos_o, kPhiWo));
        auto check_sample = [&](double lobe, double u1, double u2) {
          typename L::BsdfSample s = L::sample_bsdf(m, n, wo, R(lobe), L::v2(u1, u2));
          ASSERT_TRUE(finite(to_d(s.wi)) && finite(to_d(s.weight)) && std::isfinite(double(s.pdf)));
          ASSERT_TRUE(s.weight.x >= 0 && s.weight.y >= 0 && s.weight.z >= 0 && s.pdf >= 0);
          if (s.valid && !s.delta) {
            ASSERT_GT(s.pdf, R(0));
          }
          ++checked;
        };
        for (double a : extremes)
          for (double b : extremes)
            for (double c : extremes) check_sample(a, b, c);
        for (int i = 0; i < 300; ++i) check_sample(u(), u(), u());
        std::vector<dvec3> wis = {kNormal, -kNormal, -to_d(wo), to_d(wo), frame.to_world(1e-4, 2.0),
                                  frame.to_world(-1e-4, 2.0), frame.to_world(-cos_o, kPhiWo)};
        for (int i = 0; i < 100; ++i) wis.push_back(u.unit_vector());
        for (dvec3 wi : wis) {
          dvec3 f = to_d(L::eval_bsdf(m, n, wo, L::v3(wi)));
          double pdf = double(L::pdf_bsdf(m, n, wo, L::v3(wi)));
          ASSERT_TRUE(finite(f) && std::isfinite(pdf)) << wi.x << " " << wi.y << " " << wi.z;
          ASSERT_TRUE(f.x >= 0 && f.y >= 0 && f.z >= 0 && pdf >= 0);
        }
      }
    }
  EXPECT_GT(checked, 10000);
}

}  // namespace
}  // namespace glint::shader_test
