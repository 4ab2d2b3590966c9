// Shared helpers of the shader-maths tests (shader_*_test.cpp): the float and double builds of
// shaders/lib/*.glsl behind one interface for typed tests, a fixed-seed uniform generator,
// chi-square goodness of fit with pooling of sparse cells, and adaptive quadrature.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/shader_lib.h"
#include "shader_lib_double.h"

namespace glint::shader_test {

// The traits below call functions of the shader library, which has internal linkage (an
// anonymous namespace in every translation unit), so they get internal linkage too.
namespace {

// One build of the shader library (namespace NS, scalar type RealT) as a type, so that typed
// tests run the same body in float and in double. Every function forwards unchanged.
#define GLINT_SHADER_FWD(NS, fn) \
  static auto fn(auto... a) { return NS::fn(a...); }
#define GLINT_SHADER_LIB_TRAITS(Traits, NS, RealT, Label)                                      \
  struct Traits {                                                                              \
    using Real = RealT;                                                                        \
    using vec2 = NS::vec2;                                                                     \
    using vec3 = NS::vec3;                                                                     \
    using vec4 = NS::vec4;                                                                     \
    using mat3 = NS::mat3;                                                                     \
    using Ray = NS::Ray;                                                                       \
    using SurfaceMaterial = NS::SurfaceMaterial;                                               \
    using BsdfSample = NS::BsdfSample;                                                         \
    using QuadHit = NS::QuadHit;                                                               \
    using BilinearTaps = NS::BilinearTaps;                                                     \
    using LightSample = NS::LightSample;                                                       \
    using EnvironmentSample = NS::EnvironmentSample;                                           \
    static constexpr const char* kName = Label;                                                \
    static constexpr Real kEps = std::numeric_limits<Real>::epsilon();                         \
    static Real pi() { return NS::PI; }                                                        \
    static Real no_hit() { return NS::NO_HIT; }                                                \
    static Real delta_roughness() { return NS::DELTA_ROUGHNESS; }                              \
    static constexpr int kMatte = NS::MATERIAL_MATTE;                                          \
    static constexpr int kReflective = NS::MATERIAL_REFLECTIVE;                                \
    static constexpr int kGlossy = NS::MATERIAL_GLOSSY;                                        \
    static constexpr int kTransparent = NS::MATERIAL_TRANSPARENT;                              \
    static constexpr int kRefractive = NS::MATERIAL_REFRACTIVE;                                \
    static constexpr int kFilmic = NS::TONEMAP_FILMIC;                                         \
    static constexpr int kLinear = NS::TONEMAP_LINEAR;                                         \
    GLINT_SHADER_FWD(NS, offset_surface_point)                                                 \
    GLINT_SHADER_FWD(NS, sphere_hit_point)                                                     \
    GLINT_SHADER_FWD(NS, sphere_error_scale)                                                   \
    GLINT_SHADER_FWD(NS, pcg_hash)                                                             \
    GLINT_SHADER_FWD(NS, rng_seed)                                                             \
    GLINT_SHADER_FWD(NS, rng_advance)                                                          \
    GLINT_SHADER_FWD(NS, rng_to_unit_float)                                                    \
    GLINT_SHADER_FWD(NS, sobol_dimension0)                                                     \
    GLINT_SHADER_FWD(NS, sobol_dimension1)                                                     \
    GLINT_SHADER_FWD(NS, nested_uniform_scramble)                                              \
    GLINT_SHADER_FWD(NS, sobol_pixel_seed)                                                     \
    GLINT_SHADER_FWD(NS, sobol_sample_2d)                                                      \
    GLINT_SHADER_FWD(NS, sobol_sample_1d)                                                      \
    GLINT_SHADER_FWD(NS, sobol_sample_4d)                                                      \
    GLINT_SHADER_FWD(NS, sobol_dimension2)                                                     \
    GLINT_SHADER_FWD(NS, sobol_dimension3)                                                     \
    GLINT_SHADER_FWD(NS, direction_to_uv)                                                      \
    GLINT_SHADER_FWD(NS, uv_to_direction)                                                      \
    GLINT_SHADER_FWD(NS, environment_uv)                                                       \
    GLINT_SHADER_FWD(NS, bilinear_taps)                                                        \
    GLINT_SHADER_FWD(NS, basis_from_normal)                                                    \
    GLINT_SHADER_FWD(NS, sample_disk)                                                          \
    GLINT_SHADER_FWD(NS, sample_cosine_hemisphere)                                             \
    GLINT_SHADER_FWD(NS, fresnel_schlick)                                                      \
    GLINT_SHADER_FWD(NS, dielectric_f0)                                                        \
    GLINT_SHADER_FWD(NS, fresnel_dielectric)                                                   \
    GLINT_SHADER_FWD(NS, refract_direction)                                                    \
    GLINT_SHADER_FWD(NS, ggx_distribution)                                                     \
    GLINT_SHADER_FWD(NS, smith_g1)                                                             \
    GLINT_SHADER_FWD(NS, smith_g1_over_cos)                                                    \
    GLINT_SHADER_FWD(NS, ggx_visible_normal_pdf)                                               \
    GLINT_SHADER_FWD(NS, sample_ggx_visible_normal)                                            \
    GLINT_SHADER_FWD(NS, intersect_sphere)                                                     \
    GLINT_SHADER_FWD(NS, intersect_unit_sphere)                                                \
    GLINT_SHADER_FWD(NS, intersect_triangle)                                                   \
    GLINT_SHADER_FWD(NS, intersect_quad)                                                       \
    GLINT_SHADER_FWD(NS, intersect_planar_quad)                                                \
    GLINT_SHADER_FWD(NS, quad_normal)                                                          \
    GLINT_SHADER_FWD(NS, is_delta_material)                                                    \
    GLINT_SHADER_FWD(NS, eval_bsdf)                                                            \
    GLINT_SHADER_FWD(NS, pdf_bsdf)                                                             \
    GLINT_SHADER_FWD(NS, sample_bsdf)                                                          \
    GLINT_SHADER_FWD(NS, tonemap_channel)                                                      \
    GLINT_SHADER_FWD(NS, tonemap)                                                              \
    GLINT_SHADER_FWD(NS, sample_sphere_light)                                                  \
    GLINT_SHADER_FWD(NS, sphere_light_pdf)                                                     \
    GLINT_SHADER_FWD(NS, sample_quad_light)                                                    \
    GLINT_SHADER_FWD(NS, sample_parallelogram_light)                                           \
    GLINT_SHADER_FWD(NS, parallelogram_light_pdf)                                              \
    GLINT_SHADER_FWD(NS, quad_light_pdf)                                                       \
    GLINT_SHADER_FWD(NS, power_heuristic)                                                      \
    GLINT_SHADER_FWD(NS, sample_environment)                                                   \
    GLINT_SHADER_FWD(NS, environment_pdf)                                                      \
    static vec3 v3(double x, double y, double z) { return vec3(Real(x), Real(y), Real(z)); }   \
    static vec3 v3(glm::dvec3 v) { return vec3(Real(v.x), Real(v.y), Real(v.z)); }             \
    static vec2 v2(double x, double y) { return vec2(Real(x), Real(y)); }                      \
    static Ray ray(glm::dvec3 o, glm::dvec3 d) { return Ray(v3(o), v3(d)); }                   \
  };

GLINT_SHADER_LIB_TRAITS(FloatLib, ::glint::gpu, float, "Float")
GLINT_SHADER_LIB_TRAITS(DoubleLib, ::glint::gpu_double, double, "Double")
#undef GLINT_SHADER_LIB_TRAITS
#undef GLINT_SHADER_FWD

using Precisions = ::testing::Types<FloatLib, DoubleLib>;

// Test names ShaderX/Float.Name and ShaderX/Double.Name.
struct PrecisionName {
  template <class T>
  static std::string GetName(int) {
    return T::kName;
  }
};

}  // namespace

inline glm::dvec3 to_d(glm::vec3 v) { return glm::dvec3(v); }
inline glm::dvec3 to_d(glm::dvec3 v) { return v; }
inline glm::dvec2 to_d(glm::vec2 v) { return glm::dvec2(v); }
inline glm::dvec2 to_d(glm::dvec2 v) { return v; }

// Uniform numbers in [0,1) with 24 random bits: exactly representable in float, so float and
// double runs see the same values, and never 1 (the shader's rng_to_unit_float is the same).
class Uniform {
 public:
  explicit Uniform(std::uint64_t seed) : engine_(seed) {}
  double operator()() { return double(engine_() >> 40) * 0x1.0p-24; }
  glm::dvec2 vec2() {
    double x = (*this)();
    return {x, (*this)()};
  }
  // A uniformly distributed unit vector.
  glm::dvec3 unit_vector() {
    double z = 1.0 - 2.0 * (*this)();
    double phi = 2.0 * std::numbers::pi * (*this)();
    double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
  }

 private:
  std::mt19937_64 engine_;
};

// An orthonormal frame (t, b, n) built without the library, for binning directions.
struct Frame {
  glm::dvec3 t, b, n;
  explicit Frame(glm::dvec3 normal) : n(glm::normalize(normal)) {
    glm::dvec3 a = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    t = glm::normalize(glm::cross(a, n));
    b = glm::cross(n, t);
  }
  glm::dvec3 to_world(double cos_theta, double phi) const {
    double s = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    return s * std::cos(phi) * t + s * std::sin(phi) * b + cos_theta * n;
  }
  double cos_theta(glm::dvec3 w) const { return glm::dot(w, n); }
  // phi in [0, 2pi)
  double phi(glm::dvec3 w) const {
    double p = std::atan2(glm::dot(w, b), glm::dot(w, t));
    return p < 0.0 ? p + 2.0 * std::numbers::pi : p;
  }
};

// The bin of direction w in a grid of n_cos equal bins of cos(theta) over [-1, 1] (both
// hemispheres) times n_phi equal bins of azimuth, as index cos_bin * n_phi + phi_bin: equal
// solid angles, so each bin's probability is the pdf's integral over it.
inline int sphere_bin(const Frame& frame, glm::dvec3 w, int n_cos, int n_phi) {
  int ci = std::clamp(int((frame.cos_theta(w) + 1.0) * 0.5 * n_cos), 0, n_cos - 1);
  int pj = std::clamp(int(frame.phi(w) / (2 * std::numbers::pi) * n_phi), 0, n_phi - 1);
  return ci * n_phi + pj;
}

// Regularised upper incomplete gamma function Q(a, x) (series for x < a + 1, Lentz's continued
// fraction otherwise; Numerical Recipes 6.2). The p-value of a chi-square statistic x with k
// degrees of freedom is Q(k/2, x/2).
inline double gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  double log_prefix = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1.0) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 100000; ++n) {
      term *= x / (a + n);
      sum += term;
      if (std::abs(term) < std::abs(sum) * 1e-15) break;
    }
    return std::max(0.0, 1.0 - sum * std::exp(log_prefix));
  }
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-15) break;
  }
  return std::exp(log_prefix) * h;
}

inline double chi_square_p_value(double statistic, int dof) {
  return gamma_q(0.5 * dof, 0.5 * statistic);
}

struct ChiSquareResult {
  double statistic = 0;
  int dof = 0;
  double p_value = 1;
  std::string problem;  // non-empty when a cell has samples but zero expected count
  std::string describe() const {
    std::ostringstream s;
    s << "chi2 = " << statistic << " with " << dof << " dof, p = " << p_value;
    if (!problem.empty()) s << "; " << problem;
    return s.str();
  }
};

// Pearson's chi-square test of observed against expected cell counts. Cells whose expected
// count is below min_expected are pooled (smallest first) until each pool reaches it, so the
// chi-square approximation holds; a remainder joins the last pool. A cell with observations
// but an expected count of exactly zero (the pdf says impossible) is a failure by itself.
inline ChiSquareResult chi_square_test(const std::vector<double>& observed,
                                       const std::vector<double>& expected,
                                       double min_expected = 5.0) {
  ChiSquareResult r;
  std::vector<std::size_t> order(observed.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return expected[a] < expected[b]; });
  std::vector<std::pair<double, double>> cells;  // (observed, expected)
  double pool_o = 0, pool_e = 0;
  for (std::size_t i : order) {
    if (expected[i] == 0.0 && observed[i] > 0.0 && r.problem.empty()) {
      r.problem = "cell " + std::to_string(i) + " has " + std::to_string(int(observed[i])) +
                  " samples where the pdf is zero";
    }
    if (expected[i] >= min_expected && pool_e == 0.0) {
      cells.push_back({observed[i], expected[i]});
      continue;
    }
    pool_o += observed[i];
    pool_e += expected[i];
    if (pool_e >= min_expected) {
      cells.push_back({pool_o, pool_e});
      pool_o = pool_e = 0;
    }
  }
  if (pool_e > 0.0 || pool_o > 0.0) {
    if (cells.empty()) {
      cells.push_back({pool_o, pool_e});
    } else {
      cells.back().first += pool_o;
      cells.back().second += pool_e;
    }
  }
  for (auto [o, e] : cells) r.statistic += e > 0.0 ? (o - e) * (o - e) / e : (o > 0 ? 1e300 : 0);
  r.dof = int(cells.size()) - 1;
  r.p_value = r.dof > 0 ? chi_square_p_value(r.statistic, r.dof) : 1.0;
  return r;
}

// Significance level of every goodness-of-fit test in these files. The seeds are fixed, so a
// test either always passes or always fails; 1e-4 keeps the chance that a correct sampler
// fails any of the ~100 tests below about 1%.
constexpr double kChiSquareAlpha = 1e-4;

// Adaptive Simpson quadrature of f on [a, b], starting from `pieces` equal subintervals and
// splitting any whose two-half estimate differs from the whole by more than 15 * tol (tol
// halves with each split) or, for large values, by more than 1e-12 relative (so that rounding
// noise cannot force every branch down to max_depth).
inline double adaptive_simpson(const std::function<double(double)>& f, double a, double b,
                               double tol, int pieces = 4, int max_depth = 24) {
  struct Rec {
    static double run(const std::function<double(double)>& f, double a, double b, double fa,
                      double fm, double fb, double whole, double tol, int depth) {
      double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
      double flm = f(lm), frm = f(rm);
      double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
      double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
      double diff = left + right - whole;
      if (depth <= 0 || std::abs(diff) <= 15.0 * std::max(tol, 1e-12 * std::abs(left + right))) {
        return left + right + diff / 15.0;
      }
      return run(f, a, m, fa, flm, fm, left, 0.5 * tol, depth - 1) +
             run(f, m, b, fm, frm, fb, right, 0.5 * tol, depth - 1);
    }
  };
  double sum = 0;
  for (int i = 0; i < pieces; ++i) {
    double x0 = a + (b - a) * i / pieces, x1 = a + (b - a) * (i + 1) / pieces;
    double xm = 0.5 * (x0 + x1);
    double f0 = f(x0), fm = f(xm), f1 = f(x1);
    sum += Rec::run(f, x0, x1, f0, fm, f1, (x1 - x0) / 6.0 * (f0 + 4.0 * fm + f1), tol / pieces,
                    max_depth);
  }
  return sum;
}

// Adaptive Simpson over [a, b] split first at every breakpoint inside it (the known peaks of
// an integrand, which a coarse first sampling could otherwise step over).
inline double integrate_with_breaks(const std::function<double(double)>& f, double a, double b,
                                    std::vector<double> breaks, double tol) {
  std::vector<double> xs{a};
  std::sort(breaks.begin(), breaks.end());
  for (double x : breaks)
    if (x > a && x < b) xs.push_back(x);
  xs.push_back(b);
  double sum = 0;
  for (std::size_t i = 0; i + 1 < xs.size(); ++i)
    sum += adaptive_simpson(f, xs[i], xs[i + 1], tol * (xs[i + 1] - xs[i]) / (b - a));
  return sum;
}

// Adaptive 2D quadrature of f(x, y) over a rectangle: each cell gets a 4x4 Gauss-Legendre
// rule and is split into quarters while the quarters' sum differs from the cell's own value
// by more than its share of tol (by area) and more than 1e-9 relative. Refinement is local
// in both directions, so a narrow peak costs a few hundred cells, not a nested 1D refinement
// along every line through it. The rectangle is split first at the breakpoints.
class Quadrature2d {
 public:
  using Fn = std::function<double(double, double)>;
  Quadrature2d(Fn f, double tol, int max_depth = 14) : f_(std::move(f)), tol_(tol), max_depth_(max_depth) {}

  double integrate(double x0, double x1, double y0, double y1, std::vector<double> bx,
                   std::vector<double> by) {
    area_ = (x1 - x0) * (y1 - y0);
    std::vector<double> xs = splits(x0, x1, bx), ys = splits(y0, y1, by);
    double sum = 0;
    for (std::size_t i = 0; i + 1 < xs.size(); ++i)
      for (std::size_t j = 0; j + 1 < ys.size(); ++j) {
        double v = rule(xs[i], xs[i + 1], ys[j], ys[j + 1]);
        sum += refine(xs[i], xs[i + 1], ys[j], ys[j + 1], v, max_depth_);
      }
    return sum;
  }

 private:
  static std::vector<double> splits(double a, double b, std::vector<double> breaks) {
    std::vector<double> xs{a};
    std::sort(breaks.begin(), breaks.end());
    for (double x : breaks)
      if (x > a && x < b) xs.push_back(x);
    xs.push_back(b);
    return xs;
  }
  double rule(double x0, double x1, double y0, double y1) const {
    static const double node[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                   0.8611363115940526};
    static const double weight[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                     0.3478548451374538};
    double hx = 0.5 * (x1 - x0), hy = 0.5 * (y1 - y0), cx = x0 + hx, cy = y0 + hy, sum = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) sum += weight[i] * weight[j] * f_(cx + hx * node[i], cy + hy * node[j]);
    return sum * hx * hy;
  }
  double refine(double x0, double x1, double y0, double y1, double whole, int depth) const {
    double xm = 0.5 * (x0 + x1), ym = 0.5 * (y0 + y1);
    double q[4] = {rule(x0, xm, y0, ym), rule(xm, x1, y0, ym), rule(x0, xm, ym, y1), rule(xm, x1, ym, y1)};
    double parts = q[0] + q[1] + q[2] + q[3];
    double share = tol_ * (x1 - x0) * (y1 - y0) / area_;
    if (depth <= 0 || std::abs(parts - whole) <= std::max(share, 1e-9 * std::abs(parts))) return parts;
    return refine(x0, xm, y0, ym, q[0], depth - 1) + refine(xm, x1, y0, ym, q[1], depth - 1) +
           refine(x0, xm, ym, y1, q[2], depth - 1) + refine(xm, x1, ym, y1, q[3], depth - 1);
  }

  Fn f_;
  double tol_;
  int max_depth_;
  double area_ = 1;
};

// |a - b| <= tol * max(|a|, |b|, floor): a relative comparison that tolerates zeros.
inline bool near_rel(double a, double b, double tol, double floor = 1e-30) {
  return std::abs(a - b) <= tol * std::max({std::abs(a), std::abs(b), floor});
}

}  // namespace glint::shader_test
