// The materials of docs/DESIGN.md §7 (shaders/lib/bsdf.glsl) in float and double: sampling agrees
// with eval and pdf, sampled directions follow the pdf (chi-square), the pdf integrates to the
// valid-sample fraction, white materials do not create energy, reciprocity, the delta lobes,
// and no NaN or Inf anywhere in the parameter range.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
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
class ShaderBsdf : public ::testing::Test {};
TYPED_TEST_SUITE(ShaderBsdf, Precisions, PrecisionName);

struct MaterialCase {
  const char* name;
  int type;  // MATERIAL_* of bsdf.glsl: matte 0, reflective 1, glossy 2, transparent 3
  double roughness;
};
// The non-delta materials of the brief: matte, rough metal, glossy at the smallest coat
// roughness (alpha = 0.03^2) and a rough one, and rough thin glass.
const MaterialCase kRoughCases[] = {{"matte", 0, 0.0},      {"reflective 0.2", 1, 0.2},
                                    {"reflective 0.5", 1, 0.5}, {"glossy 0", 2, 0.0},
                                    {"glossy 0.3", 2, 0.3}, {"transparent 0.3", 3, 0.3}};
// n.wo of the outgoing directions: normal incidence, oblique, and grazing.
const double kCosWo[] = {1.0, 0.7, 0.3, 0.05};
const double kPhiWo = 1.0;
const double kIor = 1.5;
// A tilted shading normal, so that the tests go through basis_from_normal's general case.
const dvec3 kNormal = glm::normalize(dvec3(0.3, -0.4, 0.866));

template <class L>
typename L::SurfaceMaterial material(const MaterialCase& c, dvec3 color) {
  using R = typename L::Real;
  return typename L::SurfaceMaterial{c.type, L::v3(color), R(c.roughness), R(kIor)};
}

// Schlick's Fresnel written out (docs/DESIGN.md §7).
double schlick(double f0, double cos_theta) { return f0 + (1 - f0) * std::pow(1 - std::abs(cos_theta), 5); }
double dielectric_f0(double ior) { return std::pow((ior - 1) / (ior + 1), 2); }

bool finite(dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// (a) For every non-delta sample, weight = eval / pdf and pdf = pdf_bsdf at the sampled
// direction, to a few eps (they are the same computations in the same precision); wi is unit
// and on the side of the lobe it came from.
TYPED_TEST(ShaderBsdf, SampleAgreesWithEvalAndPdf) {
  using L = TypeParam;
  const Frame frame(kNormal);
  const typename L::vec3 n = L::v3(kNormal);
  Uniform u(31);
  for (const MaterialCase& c : kRoughCases) {
    for (double cos_o : kCosWo) {
      SCOPED_TRACE(std::string(c.name) + ", n.wo = " + std::to_string(cos_o));
      typename L::SurfaceMaterial m = material<L>(c, {0.8, 0.6, 0.4});
      typename L::vec3 wo = L::v3(frame.to_world(cos_o, kPhiWo));
      int valid = 0;
      for (int i = 0; i < 20000; ++i) {
        typename L::BsdfSample s = L::sample_bsdf(m, n, wo, typename L::Real(u()), L::v2(u(), u()));
        if (!s.valid) continue;
        ++valid;
        ASSERT_FALSE(s.delta);
        ASSERT_NEAR(glm::length(to_d(s.wi)), 1.0, 16 * L::kEps);
        if (c.type != L::kTransparent) {
          ASSERT_GT(glm::dot(s.wi, n), 0);
        }
        double pdf = double(L::pdf_bsdf(m, n, wo, s.wi));
        ASSERT_GT(pdf, 0.0);
        ASSERT_TRUE(near_rel(double(s.pdf), pdf, 4 * L::kEps)) << s.pdf << " vs " << pdf;
        dvec3 expected = to_d(L::eval_bsdf(m, n, wo, s.wi)) / double(s.pdf);
        for (int k = 0; k < 3; ++k) {
          ASSERT_TRUE(near_rel(double(s.weight[k]), expected[k], 8 * L::kEps, 1e-30))
              << s.weight[k] << " vs " << expected[k];
        }
      }
      EXPECT_GT(valid, 10000);
    }
  }
}

// The probability of each (cos theta, phi) bin under pdf_bsdf (double build): the integral
// of pdf sin(theta) over the bin in (theta, phi) by adaptive 2D Gauss-Legendre (tolerance
// 1e-8 per bin), split first at the specular peaks (theta_o and pi - theta_o, phi_o + pi)
// so that narrow lobes are found.
std::vector<double> bin_probabilities(const DoubleLib::SurfaceMaterial& m, const Frame& frame,
                                      dvec3 n, dvec3 wo, int n_cos, int n_phi) {
  double theta_o = std::acos(std::clamp(frame.cos_theta(wo), -1.0, 1.0));
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
      probs[i * n_phi + j] = quadrature.integrate(t0, t1, p0, p1, {theta_o, kPi - theta_o}, {phi_peak});
    }
  }
  return probs;
}

// (b) Chi-square goodness of fit of sampled directions against pdf_bsdf over 40 cos(theta)
// bins on [-1, 1] times 32 azimuth bins, 2e5 samples per case; cells with an expected count
// below 5 are pooled; significance kChiSquareAlpha. (c) On the same run: the pdf's integral
// over the sphere (the sum of the bin probabilities, quadrature error below 1e-5) equals the
// fraction of valid samples, within 4.5 binomial standard errors sqrt(p (1 - p) / N) of the
// invalid fraction p plus the quadrature error.
TYPED_TEST(ShaderBsdf, SampledDirectionsFollowThePdf) {
  using L = TypeParam;
  const int n_cos = 40, n_phi = 32, n = 200000;
  const Frame frame(kNormal);
  const typename L::vec3 nl = L::v3(kNormal);
  Uniform u(32);
  for (const MaterialCase& c : kRoughCases) {
    for (double cos_o : kCosWo) {
      SCOPED_TRACE(std::string(c.name) + ", n.wo = " + std::to_string(cos_o));
      typename L::SurfaceMaterial m = material<L>(c, {0.8, 0.6, 0.4});
      typename L::vec3 wo = L::v3(frame.to_world(cos_o, kPhiWo));
      // The reference pdf is evaluated at the inputs as rounded to the precision under test;
      // n and wo are renormalised: a float-rounded normal is unit only to ~eps, which moves
      // cos(theta_h) = n.h by ~eps, and at the glossy coat's alpha = 0.03^2 the peak of D
      // depends on 1 - cos^2 at the level alpha^2 = 8e-7 (a 10% change of the reference).
      DoubleLib::SurfaceMaterial md{c.type, dvec3(0.8, 0.6, 0.4), double(m.roughness), double(m.ior)};
      std::vector<double> probs = bin_probabilities(md, frame, glm::normalize(to_d(nl)),
                                                    glm::normalize(to_d(wo)), n_cos, n_phi);
      std::vector<double> observed(probs.size(), 0.0), expected(probs.size());
      int invalid = 0;
      for (int i = 0; i < n; ++i) {
        typename L::BsdfSample s = L::sample_bsdf(m, nl, wo, typename L::Real(u()), L::v2(u(), u()));
        if (!s.valid) {
          ++invalid;
          continue;
        }
        dvec3 wi = glm::normalize(to_d(s.wi));
        observed[sphere_bin(frame, wi, n_cos, n_phi)] += 1;
      }
      double total = 0;
      for (std::size_t k = 0; k < probs.size(); ++k) {
        expected[k] = n * probs[k];
        total += probs[k];
      }
      ChiSquareResult r = chi_square_test(observed, expected);
      EXPECT_TRUE(r.problem.empty()) << r.describe();
      EXPECT_GE(r.p_value, kChiSquareAlpha) << r.describe();

      double p_invalid = double(invalid) / n;
      double se = std::sqrt(std::max(p_invalid * (1 - p_invalid), 1.0 / n) / n);
      EXPECT_NEAR(total, 1.0 - p_invalid, 4.5 * se + 1e-5)
          << "integral of the pdf " << total << ", invalid fraction " << p_invalid;
    }
  }
}

// The coat's share of a glossy surface's albedo is at most the visible-normal average of its
// Fresnel term, F_vis = E[F(F0, h.wo) G1(wo) max(0, wo.h) / (n.wo n.h)] over h ~ D(h) n.h
// (the weights average to 1: the projected area of the visible microfacets is n.wo); the
// Lambertian base adds (1 - F(F0, n.wo)). Estimated with the reference sampler of D(h) n.h
// (ggx_reference.h, independent of sample_bsdf's), the double build's Smith G1 and an
// independent Fresnel; returns (F_vis, its standard error).
std::pair<double, double> glossy_coat_bound(double roughness, double cos_o, Uniform& u, int n) {
  const Frame local(dvec3(0, 0, 1));
  const dvec3 wo = local.to_world(cos_o, 0.0);
  const double alpha = std::pow(std::max(roughness, 0.03), 2);
  const double f0 = dielectric_f0(kIor);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    dvec3 h = walter_ggx_normal(alpha, u.vec2());
    double cos_oh = glm::dot(wo, h);
    double v = cos_oh <= 0 ? 0.0
                           : schlick(f0, cos_oh) * DoubleLib::smith_g1(alpha, cos_o) * cos_oh / (cos_o * h.z);
    sum += v;
    sum2 += v * v;
  }
  double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

// (d) White materials do not create energy: the albedo E[weight] (invalid samples count 0,
// 1e5 samples, standard error from the sample variance) is at most 1 + 4 SE. A white matte
// surface returns exactly 1 for every sample.
// Glossy is the exception the model allows (docs/DESIGN.md §7): its base is scaled by
// 1 - F(n.wo) while its coat reflects with F(h.wi), which varies over the lobe, so the two do
// not sum to exactly 1 and a white glossy surface can reflect slightly more than it receives
// (about 1.0008 at roughness 0.2 to 0.3 and n.wo 0.5 to 0.7, in both precisions). Its bound is
// the model's own: albedo <= 1 - F(F0, n.wo) + F_vis (glossy_coat_bound), within 4 combined SE.
TYPED_TEST(ShaderBsdf, WhiteMaterialsConserveEnergy) {
  using L = TypeParam;
  using R = typename L::Real;
  const int n = 100000;
  const Frame frame(kNormal);
  const typename L::vec3 nl = L::v3(kNormal);
  std::vector<MaterialCase> cases(std::begin(kRoughCases), std::end(kRoughCases));
  cases.push_back({"reflective 0 (mirror)", 1, 0.0});
  cases.push_back({"transparent 0 (smooth)", 3, 0.0});
  cases.push_back({"reflective 1", 1, 1.0});
  cases.push_back({"glossy 0.2", 2, 0.2});
  cases.push_back({"glossy 1", 2, 1.0});
  cases.push_back({"transparent 1", 3, 1.0});
  Uniform u(33);
  for (const MaterialCase& c : cases) {
    for (double cos_o : {1.0, 0.7, 0.5, 0.3, 0.05, 0.01}) {
      SCOPED_TRACE(std::string(c.name) + ", n.wo = " + std::to_string(cos_o));
      typename L::SurfaceMaterial m = material<L>(c, {1, 1, 1});
      typename L::vec3 wo = L::v3(frame.to_world(cos_o, kPhiWo));
      double sum = 0, sum2 = 0;
      int invalid = 0;
      for (int i = 0; i < n; ++i) {
        typename L::BsdfSample s = L::sample_bsdf(m, nl, wo, R(u()), L::v2(u(), u()));
        double w = 0;
        if (s.valid) {
          w = double(s.weight.x);
          ASSERT_EQ(s.weight.x, s.weight.y);
          ASSERT_EQ(s.weight.x, s.weight.z);
          if (c.type == L::kMatte) {
            ASSERT_EQ(s.weight.x, R(1));
          }
        } else {
          ++invalid;
        }
        sum += w;
        sum2 += w * w;
      }
      double mean = sum / n;
      double se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
      if (c.type == L::kGlossy) {
        auto [f_vis, se_f] = glossy_coat_bound(c.roughness, double(glm::dot(nl, wo)), u, n);
        double bound = 1.0 - schlick(dielectric_f0(kIor), double(glm::dot(nl, wo))) + f_vis;
        EXPECT_LE(mean, bound + 4 * std::sqrt(se * se + se_f * se_f))
            << "albedo " << mean << " +- " << se << ", bound " << bound << " +- " << se_f;
      } else {
        EXPECT_LE(mean, 1.0 + 4 * se) << "albedo " << mean << " +- " << se;
      }
      // Matte: cos(theta) = 0 (a sample on the disk's rim) is the only invalid case, 2^-22 per
      // sample at most with 24-bit u.
      if (c.type == L::kMatte) {
        EXPECT_LE(invalid, 1);
      }
    }
  }
}

// (e) eval(wo, wi) / |n.wi| = eval(wi, wo) / |n.wo| for matte and reflective, and for thin
// glass in both lobes (its transmission, mirrored through the plane, is reciprocal too; the
// normal is flipped to the new wo's side). Tolerance: 64 eps for the handful of correctly
// rounded factors, which the two sides multiply in different orders, plus the conditioning
// of what the two sides compute differently: the cosines n.wo and n.wi themselves (a dot
// product of unit vectors has a relative error of ~eps / |cos|); D, whose argument is ~2 eps
// off, with d ln D / d cos(theta_h) = 4 c (1 - a^2) / d, d = c^2 (a^2 - 1) + 1 (a =
// alpha), up to 4 / a^2 at the peak; and Fresnel, with d ln F / dx = 5 (1 - F0) (1 - x)^4 / F
// for reflection and the same over 1 - F for transmission (which grows like 1 / x as h.wo
// goes to 0). Glossy's Lambertian base is scaled by 1 - F(n.wo) and is not reciprocal by
// design: finite and non-negative only.
TYPED_TEST(ShaderBsdf, ReciprocityAndGlossyFinite) {
  using L = TypeParam;
  const Frame frame(kNormal);
  const dvec3 nd = kNormal;
  Uniform u(34);
  const MaterialCase cases[] = {{"matte", 0, 0.0},         {"reflective 0.2", 1, 0.2},
                                {"reflective 0.5", 1, 0.5}, {"reflective 1", 1, 1.0},
                                {"transparent 0.3", 3, 0.3}, {"glossy 0", 2, 0.0},
                                {"glossy 0.3", 2, 0.3}};
  for (const MaterialCase& c : cases) {
    SCOPED_TRACE(c.name);
    typename L::SurfaceMaterial m = material<L>(c, {0.9, 0.5, 0.2});
    const double a2 = std::pow(c.roughness, 4);  // (alpha = roughness^2)^2
    int compared = 0;
    for (int i = 0; i < 20000; ++i) {
      double co = 0.02 + 0.98 * u();
      double ci = (c.type == L::kTransparent && i % 2 ? -1.0 : 1.0) * (0.02 + 0.98 * u());
      dvec3 wo = frame.to_world(co, 2 * kPi * u());
      dvec3 wi = frame.to_world(ci, 2 * kPi * u());
      typename L::vec3 n = L::v3(nd);
      typename L::vec3 n_swapped = L::v3(ci > 0 ? nd : -nd);  // flipped to wi's side
      dvec3 f_oi = to_d(L::eval_bsdf(m, n, L::v3(wo), L::v3(wi)));
      dvec3 f_io = to_d(L::eval_bsdf(m, n_swapped, L::v3(wi), L::v3(wo)));
      ASSERT_TRUE(finite(f_oi) && finite(f_io));
      ASSERT_TRUE(f_oi.x >= 0 && f_oi.y >= 0 && f_oi.z >= 0 && f_io.x >= 0 && f_io.y >= 0 && f_io.z >= 0);
      if (c.type == L::kGlossy) continue;
      const bool transmission = ci < 0;
      dvec3 wr = transmission ? wi - 2.0 * glm::dot(wi, nd) * nd : wi;  // mirrored through the plane
      dvec3 h = glm::normalize(wo + wr);
      double ch = glm::dot(nd, h), x = std::abs(glm::dot(h, wo));
      double d = ch * ch * (a2 - 1) + 1;
      double kappa_d = c.type == L::kMatte ? 0.0 : 4 * ch * (1 - a2) / d;
      double cos_i = std::abs(double(glm::dot(n, L::v3(wi))));
      double cos_o = std::abs(double(glm::dot(n, L::v3(wo))));
      for (int k = 0; k < 3; ++k) {
        double f0 = c.type == L::kReflective ? double(m.color[k]) : dielectric_f0(kIor);
        double fresnel = schlick(f0, x), slope = 5 * (1 - f0) * std::pow(1 - x, 4);
        double kappa_f = c.type == L::kMatte ? 0.0 : slope / (transmission ? 1 - fresnel : fresnel);
        double tol = L::kEps * (64 + 4 / cos_o + 4 / cos_i + 2 * kappa_d + 4 * kappa_f);
        ASSERT_TRUE(near_rel(f_oi[k] / cos_i, f_io[k] / cos_o, tol, 1e-30))
            << f_oi[k] / cos_i << " vs " << f_io[k] / cos_o << " at n.wo " << co << " n.wi " << ci
            << ", tolerance " << tol;
      }
      if (f_oi.x > 0) ++compared;
    }
    if (c.type != L::kGlossy) {
      EXPECT_GT(compared, 5000);
    }
  }
}

// (f) Delta lobes. Reflective below roughness 0.03: the mirror direction with weight
// F(color, n.wo), pdf 0, and eval/pdf 0 for any direction.
TYPED_TEST(ShaderBsdf, SmoothMetalIsAPerfectMirror) {
  using L = TypeParam;
  using R = typename L::Real;
  const Frame frame(kNormal);
  const typename L::vec3 n = L::v3(kNormal);
  const dvec3 color(0.9, 0.6, 0.3);
  Uniform u(35);
  for (double roughness : {0.0, 0.01, 0.0299}) {
    typename L::SurfaceMaterial m = material<L>({"mirror", 1, roughness}, color);
    EXPECT_TRUE(L::is_delta_material(m));
    for (double cos_o : {1.0, 0.7, 0.3, 0.05, 1e-3}) {
      typename L::vec3 wo = L::v3(frame.to_world(cos_o, kPhiWo));
      typename L::BsdfSample s = L::sample_bsdf(m, n, wo, R(u()), L::v2(u(), u()));
      ASSERT_TRUE(s.valid && s.delta);
      EXPECT_EQ(s.pdf, R(0));
      double c = double(glm::dot(n, wo));
      dvec3 mirror = 2.0 * c * to_d(n) - to_d(wo);
      EXPECT_LE(glm::length(to_d(s.wi) - mirror), 8 * L::kEps);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(double(s.weight[k]), schlick(color[k], c), 8 * L::kEps);
      EXPECT_EQ(L::eval_bsdf(m, n, wo, s.wi), L::v3(0, 0, 0));
      EXPECT_EQ(L::pdf_bsdf(m, n, wo, s.wi), R(0));
    }
  }
  typename L::SurfaceMaterial rough = material<L>({"rough", 1, 0.03}, color);
  EXPECT_FALSE(L::is_delta_material(rough));
}

// Smooth thin glass: reflection (mirror direction, weight 1) with probability F(F0, n.wo),
// otherwise straight through (-wo) tinted by the colour. The reflected fraction of 1e5 samples
// must be within 4.5 binomial standard errors of F.
TYPED_TEST(ShaderBsdf, SmoothGlassReflectsWithFresnelProbability) {
  using L = TypeParam;
  using R = typename L::Real;
  const Frame frame(kNormal);
  const typename L::vec3 n = L::v3(kNormal);
  const dvec3 color(0.9, 0.6, 0.3);
  const int samples = 100000;
  Uniform u(36);
  for (double ior : {1.5, 1.33, 2.4}) {
    for (double roughness : {0.0, 0.02}) {
      typename L::SurfaceMaterial m{L::kTransparent, L::v3(color), R(roughness), R(ior)};
      ASSERT_TRUE(L::is_delta_material(m));
      for (double cos_o : {1.0, 0.5, 0.1, 0.01}) {
        SCOPED_TRACE("ior " + std::to_string(ior) + " n.wo " + std::to_string(cos_o));
        typename L::vec3 wo = L::v3(frame.to_world(cos_o, kPhiWo));
        double c = double(glm::dot(n, wo));
        dvec3 mirror = 2.0 * c * to_d(n) - to_d(wo);
        int reflected = 0;
        for (int i = 0; i < samples; ++i) {
          typename L::BsdfSample s = L::sample_bsdf(m, n, wo, R(u()), L::v2(u(), u()));
          ASSERT_TRUE(s.valid && s.delta);
          ASSERT_EQ(s.pdf, R(0));
          if (glm::dot(s.wi, n) > R(0)) {
            ++reflected;
            ASSERT_LE(glm::length(to_d(s.wi) - mirror), 8 * L::kEps);
            ASSERT_EQ(s.weight, L::v3(1, 1, 1));
          } else {
            ASSERT_EQ(s.wi, -wo);
            ASSERT_EQ(s.weight, L::v3(color));
          }
        }
        double p = schlick(dielectric_f0(ior), c);
        double se = std::sqrt(p * (1 - p) / samples);
        EXPECT_NEAR(double(reflected) / samples, p, 4.5 * se + 1.0 / samples);
      }
    }
  }
}

// (g) No NaN or Inf: every type, roughness 0 to 1 in steps of 0.05 (and around the delta
// threshold), wo from normal to grazing (n.wo = 1e-4), random and extreme random numbers
// (0 and 1 - 2^-24); eval and pdf for random, grazing, normal and opposite directions.
TYPED_TEST(ShaderBsdf, NoNanOrInfAnywhere) {
  using L = TypeParam;
  using R = typename L::Real;
  const Frame frame(kNormal);
  const typename L::vec3 n = L::v3(kNormal);
  std::vector<double> roughnesses;
  for (int k = 0; k <= 20; ++k) roughnesses.push_back(0.05 * k);
  roughnesses.insert(roughnesses.end(), {0.0299, 0.03, 0.0301});
  const double top = 1.0 - 0x1.0p-24;
  const std::vector<double> extremes = {0.0, 0x1.0p-24, 0.5, top};
  Uniform u(37);
  int checked = 0;
  for (int type : {L::kMatte, L::kReflective, L::kGlossy, L::kTransparent}) {
    for (double roughness : roughnesses) {
      typename L::SurfaceMaterial m{type, L::v3(0.9, 0.5, 0.1), R(roughness), R(1.5)};
      for (double cos_o : {1.0, 0.5, 0.05, 1e-3, 1e-4}) {
        SCOPED_TRACE("type " + std::to_string(type) + " roughness " + std::to_string(roughness) +
                     " n.wo " + std::to_string(cos_o));
        typename L::vec3 wo = L::v3(frame.to_world(cos_o, kPhiWo));
        auto check_sample = [&](double lobe, double u1, double u2) {
          typename L::BsdfSample s = L::sample_bsdf(m, n, wo, R(lobe), L::v2(u1, u2));
          ASSERT_TRUE(finite(to_d(s.wi)) && finite(to_d(s.weight)) && std::isfinite(double(s.pdf)))
              << lobe << " " << u1 << " " << u2;
          ASSERT_TRUE(s.weight.x >= 0 && s.weight.y >= 0 && s.weight.z >= 0 && s.pdf >= 0);
          if (s.valid && !s.delta) {
            ASSERT_GT(s.pdf, R(0));
          }
          ++checked;
        };
        for (double a : extremes)
          for (double b : extremes)
            for (double c : extremes) check_sample(a, b, c);
        for (int i = 0; i < 500; ++i) check_sample(u(), u(), u());
        std::vector<dvec3> wis = {kNormal, -kNormal, -to_d(wo), to_d(wo),
                                  frame.to_world(1e-4, 2.0), frame.to_world(-1e-4, 2.0),
                                  frame.to_world(1e-4, kPhiWo + kPi), frame.to_world(-cos_o, kPhiWo)};
        for (int i = 0; i < 200; ++i) wis.push_back(u.unit_vector());
        for (dvec3 wi : wis) {
          dvec3 f = to_d(L::eval_bsdf(m, n, wo, L::v3(wi)));
          double pdf = double(L::pdf_bsdf(m, n, wo, L::v3(wi)));
          ASSERT_TRUE(finite(f) && std::isfinite(pdf)) << wi.x << " " << wi.y << " " << wi.z;
          ASSERT_TRUE(f.x >= 0 && f.y >= 0 && f.z >= 0 && pdf >= 0);
        }
      }
    }
  }
  EXPECT_GT(checked, 100000);
}

}  // namespace
}  // namespace glint::shader_test
