// Light sampling of shaders/lib/lights.glsl in float and double: sphere cones (down to
// radius/distance 1e-8), spheres around the shading point, planar and non-planar quads seen
// head-on and at grazing angles, against their pdf functions (chi-square, normalisation,
// sampled == evaluated pdf) and against analytic irradiance and solid angles; and the power
// heuristic at zero, huge and infinite pdfs.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <glm/glm.hpp>

#include "shader_test_util.h"

namespace glint::shader_test {
namespace {

using glm::dvec3;
constexpr double kPi = std::numbers::pi;

template <class L>
class ShaderLights : public ::testing::Test {};
TYPED_TEST_SUITE(ShaderLights, Precisions, PrecisionName);

struct SphereCase {
  dvec3 p, center;
  double radius;
};

struct QuadCase {
  dvec3 p, c[4];
};

// 1 - cos(theta_max) of a sphere of radius r seen from distance d, in long double.
double exact_one_minus_cos(double r, double d) {
  long double s2 = (long double)r * r / ((long double)d * d);
  return double(s2 / (1.0L + std::sqrt(1.0L - s2)));
}

// The pdf (in L's precision) of direction w from the sphere case, via a double ray cast:
// the first hit point y, converted to L, given to sphere_light_pdf. 0 on a miss.
template <class L>
double sphere_pdf_of_direction(const SphereCase& s, dvec3 w) {
  double t = DoubleLib::intersect_sphere(DoubleLib::ray(s.p, w), s.center, s.radius, 0.0, 1e300);
  if (t == DoubleLib::no_hit()) return 0.0;
  dvec3 y = DoubleLib::sphere_hit_point(DoubleLib::ray(s.p, w), t, s.center, s.radius);
  return double(L::sphere_light_pdf(L::v3(s.p), L::v3(s.center), typename L::Real(s.radius), L::v3(y)));
}

// The density of quad area sampling towards w: the sum over the quad's triangles that the ray
// crosses (a non-planar quad can be crossed twice) of quad_light_pdf at the crossing.
template <class L>
double quad_pdf_of_direction(const QuadCase& q, dvec3 w) {
  const int tri[2][3] = {{0, 1, 2}, {1, 3, 2}};
  double sum = 0;
  for (auto& t : tri) {
    dvec3 h = DoubleLib::intersect_triangle(DoubleLib::ray(q.p, w), q.c[t[0]], q.c[t[1]], q.c[t[2]], 0.0, 1e300);
    if (h.x == DoubleLib::no_hit()) continue;
    dvec3 y = (1 - h.y - h.z) * q.c[t[0]] + h.y * q.c[t[1]] + h.z * q.c[t[2]];
    sum += double(L::quad_light_pdf(L::v3(q.p), L::v3(q.c[0]), L::v3(q.c[1]), L::v3(q.c[2]),
                                    L::v3(q.c[3]), L::v3(y)));
  }
  return sum;
}

// Chi-square of n sampled directions against pdf: cells in (cos theta, phi) around `axis`
// (the test's own frame, not the sampler's) with cos theta in [cos_min, 1]; directions outside
// go to one extra cell. Expected counts integrate the pdf over each cell (d omega =
// d cos(theta) d phi) with adaptive quadrature; their sum is returned in total_probability.
struct DirectionalFit {
  ChiSquareResult chi2;
  double total_probability = 0;
};
template <class SampleFn, class PdfFn>
DirectionalFit fit_directions(SampleFn sample, PdfFn pdf, dvec3 axis, double cos_min, int n,
                              const std::vector<dvec3>& corners = {}) {
  const int nc = 12, nphi = 16;
  Frame f(axis);
  std::vector<double> observed(nc * nphi + 1, 0.0), expected(nc * nphi + 1, 0.0);
  Uniform u(101);
  for (int i = 0; i < n; ++i) {
    dvec3 w;
    if (!sample(u.vec2(), w)) continue;
    double c = f.cos_theta(w);
    if (c < cos_min) {
      observed[nc * nphi] += 1;
      continue;
    }
    int ci = std::min(nc - 1, int((c - cos_min) / (1 - cos_min) * nc));
    int pi = std::min(nphi - 1, int(f.phi(w) / (2 * kPi) * nphi));
    observed[ci * nphi + pi] += 1;
  }
  DirectionalFit r;
  // Cells are split at the light's corners, so that no corner pokes into a cell between the
  // quadrature's nodes unseen.
  std::vector<double> break_c, break_phi;
  for (dvec3 c : corners) {
    break_c.push_back(f.cos_theta(c));
    break_phi.push_back(f.phi(c));
  }
  // 1e-6 per cell (2e-4 in all) and depth 5 (below the 6 x 6 pieces) at the rim: an error of n * 2e-4 = 40
  // counts spread over the rim's cells changes chi-square by far less than its spread.
  Quadrature2d q([&](double c, double phi) { return pdf(f.to_world(c, phi)); }, 1e-6, 5);
  for (int ci = 0; ci < nc; ++ci)
    for (int pi = 0; pi < nphi; ++pi) {
      double c0 = cos_min + (1 - cos_min) * ci / nc, c1 = cos_min + (1 - cos_min) * (ci + 1) / nc;
      double p0 = 2 * kPi * pi / nphi, p1 = 2 * kPi * (pi + 1) / nphi;
      // Each cell starts as 6 x 6 pieces (576 nodes): a light's rim cutting a cell's corner
      // between the nodes of one rule would otherwise count as nothing and never be refined.
      std::vector<double> bc = break_c, bp = break_phi;
      for (int k = 1; k < 6; ++k) {
        bc.push_back(c0 + (c1 - c0) * k / 6);
        bp.push_back(p0 + (p1 - p0) * k / 6);
      }
      double p = q.integrate(c0, c1, p0, p1, bc, bp);
      expected[ci * nphi + pi] = n * p;
      r.total_probability += p;
    }
  expected[nc * nphi] = std::max(0.0, n * (1 - r.total_probability));
  r.chi2 = chi_square_test(observed, expected);
  return r;
}

// ---------------------------------------------------------------------------------- spheres

// A cone of angular radius ~0.25 seen around an axis tilted by 0.1 rad from the cone's axis
// (cell edges cross the cone's rim); a sphere around an off-centre shading point (area
// sampling). 2e5 samples; the pdf must integrate to 1 (quadrature tolerance 2e-4 in total,
// 1e-3 allowed) and the chi-square must pass at kChiSquareAlpha.
TYPED_TEST(ShaderLights, SphereDirectionsFollowThePdf) {
  using L = TypeParam;
  const int n = 200000;
  std::vector<SphereCase> cases = {{{0.1, -0.2, 0.3}, {0.4, 0.1, 2.3}, 0.5},
                                   {{1.3, 0.6, -0.2}, {1.0, 0.5, 0.0}, 0.8}};
  for (const SphereCase& s : cases) {
    bool inside = glm::length(s.p - s.center) < s.radius;
    dvec3 to_c = glm::normalize(s.center - s.p);
    Frame tilt(to_c);
    dvec3 axis = inside ? dvec3(0.3, 0.8, -0.5) : glm::normalize(to_c + 0.1 * tilt.t);
    double cos_min = inside ? -1.0 : std::cos(std::asin(s.radius / glm::length(s.center - s.p)) + 0.15);
    auto sample = [&](glm::dvec2 u, dvec3& w) {
      auto ls = L::sample_sphere_light(L::v3(s.p), L::v3(s.center), typename L::Real(s.radius), L::v2(u.x, u.y));
      w = to_d(ls.wi);
      return ls.valid;
    };
    DirectionalFit fit = fit_directions(sample, [&](dvec3 w) { return sphere_pdf_of_direction<L>(s, w); },
                                        axis, cos_min, n);
    EXPECT_NEAR(fit.total_probability, 1.0, 1e-3) << (inside ? "inside" : "outside");
    EXPECT_TRUE(fit.chi2.problem.empty()) << fit.chi2.problem;
    EXPECT_GE(fit.chi2.p_value, kChiSquareAlpha) << (inside ? "inside: " : "outside: ") << fit.chi2.describe();
  }
}

// The sampled pdf equals sphere_light_pdf at the point where a ray along the sampled direction
// meets the sphere, and dist is that ray's distance. Outside, both are the same expression of
// |c - p| (equal exactly); inside, the area pdf at two roundings of one point: dist^2 / cos is
// conditioned by 1 / cos at the sphere, so 64 eps / cos is allowed; dist to 64 eps / cos too
// (the ray meets the sphere at angle acos(cos)).
TYPED_TEST(ShaderLights, SphereSampledPdfEqualsEvaluatedPdf) {
  using L = TypeParam;
  using R = typename L::Real;
  std::vector<SphereCase> cases = {{{0, 0, 0}, {0, 0, 3}, 1},
                                   {{0.2, 0.1, -0.3}, {5, 1, 2}, 0.01},
                                   {{0, 0, 0}, {1, 2, 3}, 1e-3},
                                   {{0, 0, 0}, {0, 0, 1.0001}, 1},  // almost on the surface
                                   {{0.3, 0.1, 0.2}, {0, 0, 0}, 1},  // inside
                                   {{0, 0, 0}, {0, 0, 0}, 2}};       // at the centre
  Uniform u(102);
  for (const SphereCase& s : cases) {
    int misses = 0;
    for (int i = 0; i < 20000; ++i) {
      auto ls = L::sample_sphere_light(L::v3(s.p), L::v3(s.center), R(s.radius), L::v2(u(), u()));
      ASSERT_TRUE(ls.valid);
      ASSERT_TRUE(std::isfinite(double(ls.pdf)) && ls.pdf > 0);
      ASSERT_NEAR(glm::length(to_d(ls.wi)), 1.0, 4 * L::kEps);
      auto ray = typename L::Ray(L::v3(s.p), ls.wi);
      R t = L::intersect_sphere(ray, L::v3(s.center), R(s.radius), R(0), R(1e30));
      if (t == L::no_hit()) {  // a direction on the cone's rim can round outside it
        ++misses;
        continue;
      }
      auto y = L::sphere_hit_point(ray, t, L::v3(s.center), R(s.radius));
      double pdf = double(L::sphere_light_pdf(L::v3(s.p), L::v3(s.center), R(s.radius), y));
      double cos_y = std::abs(glm::dot(glm::normalize(to_d(y) - s.center), to_d(ls.wi)));
      double tol = 64 * L::kEps / std::max(cos_y, 1e-3);
      ASSERT_TRUE(near_rel(pdf, double(ls.pdf), tol)) << pdf << " vs " << ls.pdf << " cos " << cos_y;
      // Distances are known to eps of the coordinates' size (p 1e-4 off the surface is 1e-4
      // from it only to eps |c - p|), and the ray's to eps / cos of that at a grazing hit.
      double scale = glm::length(s.center - s.p) + s.radius;
      ASSERT_TRUE(near_rel(double(t), double(ls.dist), tol, scale)) << t << " vs " << ls.dist;
    }
    EXPECT_LE(misses, 20) << "sphere radius " << s.radius;
  }
}

// pdf = 1 / (2 pi (1 - cos theta_max)) to a few eps of the long-double value for radius /
// distance from 0.5 down to 1e-8 (in float, 1 - sqrt(1 - s^2) is 0 below 2.4e-4), and the
// sampled directions stay inside the cone (up to the rounding of the axis, a few eps).
TYPED_TEST(ShaderLights, TinySpheresHaveFiniteExactPdfs) {
  using L = TypeParam;
  using R = typename L::Real;
  Uniform u(103);
  const dvec3 p(0.25, -0.5, 0.75);
  const dvec3 dir = glm::normalize(dvec3(1, 2, -2));
  for (double ratio : {0.5, 1e-2, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
    const double d = 1.0, r = ratio * d;
    const dvec3 c = p + d * dir;
    const double exact = 1 / (2 * kPi * exact_one_minus_cos(r, d));
    const double theta_max = std::asin(ratio);
    for (int i = 0; i < 2000; ++i) {
      auto ls = L::sample_sphere_light(L::v3(p), L::v3(c), R(r), L::v2(u(), u()));
      ASSERT_TRUE(ls.valid);
      ASSERT_TRUE(near_rel(double(ls.pdf), exact, 16 * L::kEps)) << ratio << ": " << ls.pdf << " vs " << exact;
      // The axis (c - p in L) and wi each carry a few eps of rounding in angle.
      dvec3 axis = glm::normalize(to_d(L::v3(c)) - to_d(L::v3(p)));
      dvec3 wi = to_d(ls.wi);  // atan2: acos near 1 would add the rounding of |wi| (~1e-4 rad)
      double angle = std::atan2(glm::length(glm::cross(wi, axis)), glm::dot(wi, axis));
      if (angle > 1e-3) ASSERT_LE(angle, theta_max * (1 + 8 * L::kEps)) << ratio;
      else ASSERT_LE(angle, theta_max + 16 * L::kEps) << ratio;
      // The distance to the near side is between d - r and d (to a few eps of d).
      ASSERT_GE(double(ls.dist), d - r - 8 * L::kEps) << ratio;
      ASSERT_LE(double(ls.dist), d + 8 * L::kEps) << ratio;
    }
    auto pdf = L::sphere_light_pdf(L::v3(p), L::v3(c), R(r), L::v3(c - r * dir));
    EXPECT_TRUE(near_rel(double(pdf), exact, 16 * L::kEps)) << ratio;
  }
}

// Irradiance from a sphere of radius 1e-3 at distance 1 with radiance 1e6 on a surface whose
// normal is at angle beta to the sphere's direction (the whole cap above the horizon):
// E = L pi sin^2(theta_max) cos(beta) exactly (Lambert's sphere formula). 4096 samples of
// L cos / pdf; allowed 4 sigma (sample standard deviation / sqrt(n)) plus 16 eps of rounding in
// pdf and cos (pdf and cos are within a few eps each). With 1 - cos(theta_max) formed as
// 1 - sqrt(1 - s^2) the float estimate is 6% off. Also at radius/distance 1e-6.
TYPED_TEST(ShaderLights, TinySphereIrradianceIsExact) {
  using L = TypeParam;
  using R = typename L::Real;
  const double radiance = 1e6;
  const dvec3 p(0.3, 0.2, -0.1);
  const dvec3 dir = glm::normalize(dvec3(0.2, 1, 0.1));
  Frame f(dir);
  for (double ratio : {1e-3, 1e-6}) {
    for (double beta : {0.0, 1.0}) {
      const dvec3 n = std::cos(beta) * dir + std::sin(beta) * f.t;
      const dvec3 c = p + dir;  // distance 1
      const double s2 = ratio * ratio;
      const double exact = radiance * kPi * s2 * std::cos(beta);
      Uniform u(104);
      const int count = 4096;
      double sum = 0, sum2 = 0;
      for (int i = 0; i < count; ++i) {
        auto ls = L::sample_sphere_light(L::v3(p), L::v3(c), R(ratio), L::v2(u(), u()));
        ASSERT_TRUE(ls.valid);
        double e = radiance * std::max(0.0, glm::dot(n, to_d(ls.wi))) / double(ls.pdf);
        sum += e;
        sum2 += e * e;
      }
      double mean = sum / count;
      double sigma = std::sqrt(std::max(0.0, sum2 / count - mean * mean) / (count - 1));
      EXPECT_NEAR(mean, exact, 4 * sigma + 16 * L::kEps * exact)
          << "ratio " << ratio << " beta " << beta << " sigma " << sigma;
    }
  }
}

// ------------------------------------------------------------------------------------ quads

// Solid angle of triangle (a, b, c) seen from p (Van Oosterom and Strackee 1983).
double triangle_solid_angle(dvec3 p, dvec3 a, dvec3 b, dvec3 c) {
  a -= p, b -= p, c -= p;
  double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
  double num = std::abs(glm::dot(a, glm::cross(b, c)));
  double den = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
  double o = 2 * std::atan2(num, den);
  return o < 0 ? o + 2 * kPi : o;
}

std::vector<QuadCase> quad_cases() {
  return {
      // planar rectangle, tilted, seen from the front
      {{0, 0, 0}, {{-1, -0.5, 3}, {-1, 0.7, 3.4}, {1, -0.5, 3}, {1, 0.7, 3.4}}},
      // non-planar: p3 lifted out of the plane, seen from the convex side
      {{0.2, 0.1, -0.5}, {{-1, -1, 2}, {-1, 1, 2}, {1, -1, 2}, {1.2, 1.1, 2.8}}},
      // the same quad seen from behind (both sides emit)
      {{0.2, 0.1, 5.0}, {{-1, -1, 2}, {-1, 1, 2}, {1, -1, 2}, {1.2, 1.1, 2.8}}},
  };
}

// 2e5 directions of `sample_light` (u -> LightSample) against quad_pdf_of_direction, integrated
// over (cos theta, phi) cells around the direction to the quad's centre; normalisation to 1e-3
// (quadrature tolerance 2e-4 in all).
template <class L, class SampleLight>
void expect_directions_follow_the_quad_pdf(const QuadCase& q, SampleLight sample_light) {
  dvec3 centre = 0.25 * (q.c[0] + q.c[1] + q.c[2] + q.c[3]);
  dvec3 axis = glm::normalize(centre - q.p);
  double cos_min = 1;
  for (dvec3 c : q.c) cos_min = std::min(cos_min, glm::dot(glm::normalize(c - q.p), axis));
  cos_min = std::cos(std::acos(cos_min) + 0.05);
  auto sample = [&](glm::dvec2 u, dvec3& w) {
    auto ls = sample_light(u);
    w = to_d(ls.wi);
    return ls.valid;
  };
  DirectionalFit fit = fit_directions(sample, [&](dvec3 w) { return quad_pdf_of_direction<L>(q, w); },
                                      axis, cos_min, 200000,
                                      {glm::normalize(q.c[0] - q.p), glm::normalize(q.c[1] - q.p),
                                       glm::normalize(q.c[2] - q.p), glm::normalize(q.c[3] - q.p)});
  EXPECT_NEAR(fit.total_probability, 1.0, 1e-3);
  EXPECT_TRUE(fit.chi2.problem.empty()) << fit.chi2.problem;
  EXPECT_GE(fit.chi2.p_value, kChiSquareAlpha) << fit.chi2.describe();
}

TYPED_TEST(ShaderLights, QuadDirectionsFollowThePdf) {
  using L = TypeParam;
  for (const QuadCase& q : quad_cases()) {
    expect_directions_follow_the_quad_pdf<L>(q, [&](glm::dvec2 u) {
      return L::sample_quad_light(L::v3(q.p), L::v3(q.c[0]), L::v3(q.c[1]), L::v3(q.c[2]), L::v3(q.c[3]),
                                  L::v2(u.x, u.y));
    });
  }
}

// Shading points from head-on to almost in the quad's plane (height 1e-2 .. 1e-6 of its size,
// beside it): every sample is valid with a finite pdf; quad_light_pdf at the point a ray along
// wi hits equals the sampled pdf (the cosine comes from p's height above the triangle's plane
// in both, so only the rounding of |y - p| differs: 64 eps; the ray's distance is known to
// eps / cos); and E[1 / pdf] is the sum of the two triangles' solid angles (Van Oosterom-
// Strackee; with multiplicity where the bent quad covers itself) within 4 sigma plus 64 eps.
TYPED_TEST(ShaderLights, QuadPdfsAtGrazingAnglesAreConsistent) {
  using L = TypeParam;
  using R = typename L::Real;
  const dvec3 c[4] = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, -1}, {1, 0, 1}};
  const dvec3 bent[4] = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, -1}, {1, 0.3, 1}};
  for (const dvec3* corners : {c, bent}) {
    for (double height : {1.0, 1e-2, 1e-4, 1e-6}) {
      const dvec3 p(2.5, height, 0.3);
      Uniform u(105);
      const int count = 20000;
      double sum = 0, sum2 = 0;
      int misses = 0, occluded = 0;
      for (int i = 0; i < count; ++i) {
        auto ls = L::sample_quad_light(L::v3(p), L::v3(corners[0]), L::v3(corners[1]), L::v3(corners[2]),
                                       L::v3(corners[3]), L::v2(u(), u()));
        ASSERT_TRUE(ls.valid) << height;
        ASSERT_TRUE(std::isfinite(double(ls.pdf)) && ls.pdf > 0) << height;
        double inv = 1 / double(ls.pdf);
        sum += inv;
        sum2 += inv * inv;
        auto hit = L::intersect_quad(typename L::Ray(L::v3(p), ls.wi), L::v3(corners[0]), L::v3(corners[1]),
                                     L::v3(corners[2]), L::v3(corners[3]), L::v2(0, 0), L::v2(0, 0),
                                     L::v2(0, 0), L::v2(0, 0), R(0), R(1e30));
        if (hit.t == L::no_hit()) {  // rounding of wi at the quad's edge
          ++misses;
          continue;
        }
        // The ray meets the plane at cos = height / dist: its t has eps / cos of rounding.
        double cos_y = std::max(height, 1e-300) / double(ls.dist);
        double t_tol = 64 * L::kEps / cos_y;
        auto ray = typename L::Ray(L::v3(p), ls.wi);
        bool crosses_a = L::intersect_triangle(ray, L::v3(corners[0]), L::v3(corners[1]), L::v3(corners[2]), R(0), R(1e30)).x != L::no_hit();
        bool crosses_b = L::intersect_triangle(ray, L::v3(corners[1]), L::v3(corners[3]), L::v3(corners[2]), R(0), R(1e30)).x != L::no_hit();
        if (crosses_a && crosses_b) {
          ++occluded;  // the bent quad's raised triangle hides part of the other from p
          continue;
        }
        ASSERT_TRUE(near_rel(double(hit.t), double(ls.dist), t_tol)) << height << ": " << hit.t << " vs " << ls.dist;
        double pdf = double(L::quad_light_pdf(L::v3(p), L::v3(corners[0]), L::v3(corners[1]),
                                              L::v3(corners[2]), L::v3(corners[3]), hit.position));
        ASSERT_TRUE(near_rel(pdf, double(ls.pdf), 64 * L::kEps)) << height << ": " << pdf << " vs " << ls.pdf;
      }
      if (corners == c) {
        EXPECT_EQ(occluded, 0);
      }
      EXPECT_LE(misses, count / 1000) << height;
      double mean = sum / count;
      double sigma = std::sqrt(std::max(0.0, sum2 / count - mean * mean) / (count - 1));
      double omega = triangle_solid_angle(p, corners[0], corners[1], corners[2]) +
                     triangle_solid_angle(p, corners[1], corners[3], corners[2]);
      EXPECT_NEAR(mean, omega, 4 * sigma + 64 * L::kEps * omega) << "height " << height;
    }
  }
}

// The affine sampler of parallelograms: the same density as the two-triangle sampler (uniform
// in area), so its directions must follow quad_light_pdf (the chi-square above);
// and at every sample, the pdf it returns is quad_light_pdf at the point it chose (64 eps), as
// is parallelogram_light_pdf (from p0, the unit normal and the area that the scene's tables
// hold, computed in double as renderer/gpu_scene.cpp does), and that point is
// p0 + u.x e1 + u.y e2 (the map is affine: a stratified u stays stratified).
TYPED_TEST(ShaderLights, ParallelogramSamplesFollowTheQuadPdf) {
  using L = TypeParam;
  const std::vector<QuadCase> cases = {
      // the tilted rectangle of quad_cases, from the front
      {{0, 0, 0}, {{-1, -0.5, 3}, {-1, 0.7, 3.4}, {1, -0.5, 3}, {1, 0.7, 3.4}}},
      // a skewed parallelogram seen from behind and from the side
      {{2.5, 0.3, 4.5}, {{-1, 0, 2}, {-0.2, 1.5, 2.2}, {1.3, 0.1, 2.5}, {2.1, 1.6, 2.7}}},
  };
  for (const QuadCase& q : cases) {
    const dvec3 m = glm::cross(q.c[1] - q.c[0], q.c[2] - q.c[0]);
    const auto normal = L::v3(glm::normalize(m));
    const auto area = typename L::Real(glm::length(m));
    expect_directions_follow_the_quad_pdf<L>(q, [&](glm::dvec2 u) {
      return L::sample_parallelogram_light(L::v3(q.p), L::v3(q.c[0]), L::v3(q.c[1]), L::v3(q.c[2]),
                                           normal, area, L::v2(u.x, u.y));
    });

    Uniform u(31);
    for (int i = 0; i < 2000; ++i) {
      const glm::dvec2 uv(u(), u());
      auto ls = L::sample_parallelogram_light(L::v3(q.p), L::v3(q.c[0]), L::v3(q.c[1]), L::v3(q.c[2]),
                                              normal, area, L::v2(uv.x, uv.y));
      ASSERT_TRUE(ls.valid);
      const dvec3 expected_y = q.c[0] + uv.x * (q.c[1] - q.c[0]) + uv.y * (q.c[2] - q.c[0]);
      const dvec3 y = q.p + double(ls.dist) * to_d(ls.wi);
      ASSERT_LE(glm::length(y - expected_y), 64 * L::kEps * 4.0) << i;
      const double pdf = double(L::quad_light_pdf(L::v3(q.p), L::v3(q.c[0]), L::v3(q.c[1]), L::v3(q.c[2]),
                                                  L::v3(q.c[3]), L::v3(expected_y)));
      ASSERT_TRUE(near_rel(pdf, double(ls.pdf), 64 * L::kEps)) << i << ": " << pdf << " vs " << ls.pdf;
      const double table_pdf =
          double(L::parallelogram_light_pdf(L::v3(q.p), L::v3(q.c[0]), normal, area, L::v3(expected_y)));
      ASSERT_TRUE(near_rel(table_pdf, double(ls.pdf), 64 * L::kEps)) << i << ": " << table_pdf << " vs " << ls.pdf;
    }
  }
}

// quad_light_pdf picks the triangle a point lies on: on the bent quad the two triangles have
// different normals, so the pdf at points of each must use that triangle's own.
TYPED_TEST(ShaderLights, QuadPdfUsesTheTriangleOfThePoint) {
  using L = TypeParam;
  const dvec3 c[4] = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, -1}, {1, 1, 1}};
  const dvec3 p(0.1, 3, 0.2);
  const dvec3 ya = 0.6 * c[0] + 0.2 * c[1] + 0.2 * c[2];  // on (p0, p1, p2)
  const dvec3 yb = 0.2 * c[1] + 0.6 * c[3] + 0.2 * c[2];  // on (p1, p3, p2)
  double area = 0.5 * glm::length(glm::cross(c[1] - c[0], c[2] - c[0])) +
                0.5 * glm::length(glm::cross(c[3] - c[1], c[2] - c[1]));
  auto expected = [&](dvec3 y, dvec3 a, dvec3 b, dvec3 cc) {
    dvec3 n = glm::normalize(glm::cross(b - a, cc - a));
    dvec3 w = y - p;
    return glm::dot(w, w) / (area * std::abs(glm::dot(n, glm::normalize(w))));
  };
  auto pdf = [&](dvec3 y) {
    return double(L::quad_light_pdf(L::v3(p), L::v3(c[0]), L::v3(c[1]), L::v3(c[2]), L::v3(c[3]), L::v3(y)));
  };
  EXPECT_TRUE(near_rel(pdf(ya), expected(ya, c[0], c[1], c[2]), 64 * L::kEps));
  EXPECT_TRUE(near_rel(pdf(yb), expected(yb, c[1], c[3], c[2]), 64 * L::kEps));
}

// ----------------------------------------------------------------------- power heuristic

TYPED_TEST(ShaderLights, PowerHeuristicIsSafeAtZeroHugeAndInfinitePdfs) {
  using L = TypeParam;
  using R = typename L::Real;
  const R inf = std::numeric_limits<R>::infinity();
  const R nan = std::numeric_limits<R>::quiet_NaN();
  const R big = std::numeric_limits<R>::max();
  const R tiny = std::numeric_limits<R>::denorm_min();
  auto w = [](R a, R b) { return double(L::power_heuristic(a, b)); };
  EXPECT_EQ(w(1, 1), 0.5);
  EXPECT_NEAR(w(2, 1), 0.8, 4 * L::kEps);
  EXPECT_NEAR(w(1, 3), 0.1, 4 * L::kEps);
  EXPECT_EQ(w(0, 0), 0.0);
  EXPECT_EQ(w(0, 1), 0.0);
  EXPECT_EQ(w(1, 0), 1.0);
  EXPECT_EQ(w(inf, 1), 1.0);
  EXPECT_EQ(w(1, inf), 0.0);
  EXPECT_EQ(w(inf, inf), 0.5);
  EXPECT_EQ(w(nan, 1), 0.0);
  EXPECT_EQ(w(1, nan), 1.0);
  EXPECT_EQ(w(-1, 1), 0.0);
  EXPECT_NEAR(w(big, big / 2), 0.8, 4 * L::kEps);
  EXPECT_NEAR(w(tiny * 2, tiny), 0.8, 4 * L::kEps);
  EXPECT_EQ(w(big, tiny), 1.0);
  // Complementary: w(a, b) + w(b, a) = 1 over 60 orders of magnitude.
  Uniform u(106);
  for (int i = 0; i < 10000; ++i) {
    R a = R(std::pow(10.0, 60 * u() - 30)), b = R(std::pow(10.0, 60 * u() - 30));
    double wa = w(a, b), wb = w(b, a);
    ASSERT_TRUE(std::isfinite(wa) && wa >= 0 && wa <= 1);
    ASSERT_NEAR(wa + wb, 1.0, 4 * L::kEps) << a << " " << b;
  }
}

}  // namespace
}  // namespace glint::shader_test
