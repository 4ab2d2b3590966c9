// Ray-sphere and ray-quad intersection of shaders/lib/intersect.glsl and the ray-origin offset
// of common.glsl, in float and in double (docs/DESIGN.md §6 and §8).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "shader_test_util.h"

namespace glint::shader_test {
namespace {

using glm::dvec2;
using glm::dvec3;

template <class L>
class ShaderIntersect : public ::testing::Test {};
TYPED_TEST_SUITE(ShaderIntersect, Precisions, PrecisionName);

// A unit vector perpendicular to d.
dvec3 perpendicular(dvec3 d, Uniform& u) {
  dvec3 p = glm::cross(d, u.unit_vector());
  return glm::normalize(p);
}

TYPED_TEST(ShaderIntersect, SphereHitFromOutside) {
  using L = TypeParam;
  using R = typename L::Real;
  const R inf = std::numeric_limits<R>::infinity();
  // Exact cases: t = |o - c| - r, independent of the direction's length.
  EXPECT_EQ(L::intersect_sphere(L::ray({0, 0, -5}, {0, 0, 1}), L::v3(0, 0, 0), R(1), R(0), inf), R(4));
  EXPECT_EQ(L::intersect_sphere(L::ray({0, 0, -5}, {0, 0, 2}), L::v3(0, 0, 0), R(1), R(0), inf), R(2));
  // tmax before the sphere: miss; tmin past the near root: the far root.
  EXPECT_EQ(L::intersect_sphere(L::ray({0, 0, -5}, {0, 0, 1}), L::v3(0, 0, 0), R(1), R(0), R(3.9)),
            L::no_hit());
  EXPECT_EQ(L::intersect_sphere(L::ray({0, 0, -5}, {0, 0, 1}), L::v3(0, 0, 0), R(1), R(4.5), inf), R(6));
  // Random rays from 1.5 to 10 radii away aimed inside the silhouette: the near root, on the
  // sphere to a few ulps of the distance travelled (64 eps * (|o - c| + r) allows for the
  // rounding of f, b and the square root, each a few eps of |o - c|).
  Uniform u(1);
  for (int i = 0; i < 20000; ++i) {
    double r = std::pow(10.0, -2.0 + 5.0 * u());
    dvec3 c = (u.unit_vector() * 3.0) * r;
    double dist = r * (1.5 + 8.5 * u());
    dvec3 o = c + dist * u.unit_vector();
    dvec3 to_c = glm::normalize(c - o);
    dvec3 target = c + 0.95 * r * std::sqrt(u()) * perpendicular(to_c, u);
    dvec3 d = glm::normalize(target - o) * (0.5 + u());  // directions need not be unit
    typename L::Ray ray = L::ray(o, d);
    R t = L::intersect_sphere(ray, L::v3(c), R(r), R(0), inf);
    ASSERT_GT(t, R(0)) << "miss, r = " << r << " i = " << i;
    dvec3 p = to_d(ray.origin) + double(t) * to_d(ray.direction);
    double tol = 64.0 * L::kEps * (dist + r);
    ASSERT_NEAR(glm::length(p - c), r, tol) << "r = " << r << " i = " << i;
    ASSERT_LT(glm::dot(p - c, d), 0.0) << "far root returned, i = " << i;
  }
}

TYPED_TEST(ShaderIntersect, SphereHitFromInside) {
  using L = TypeParam;
  using R = typename L::Real;
  const R inf = std::numeric_limits<R>::infinity();
  EXPECT_EQ(L::intersect_sphere(L::ray({0, 0, 0}, {0, 1, 0}), L::v3(0, 0, 0), R(2), R(0), inf), R(2));
  EXPECT_EQ(L::intersect_sphere(L::ray({0, 0.5, 0}, {0, -1, 0}), L::v3(0, 0, 0), R(2), R(0), inf),
            R(2.5));
  Uniform u(2);
  for (int i = 0; i < 20000; ++i) {
    double r = std::pow(10.0, -2.0 + 5.0 * u());
    dvec3 c = (u.unit_vector() * 3.0) * r;
    dvec3 o = c + 0.99 * r * u() * u.unit_vector();
    dvec3 d = u.unit_vector();
    typename L::Ray ray = L::ray(o, d);
    R t = L::intersect_sphere(ray, L::v3(c), R(r), R(0), inf);
    ASSERT_GT(t, R(0)) << "no exit hit, i = " << i;
    dvec3 p = to_d(ray.origin) + double(t) * to_d(ray.direction);
    ASSERT_NEAR(glm::length(p - c), r, 64.0 * L::kEps * (glm::length(c) + 2.0 * r)) << "i = " << i;
    ASSERT_GT(glm::dot(p - c, d), 0.0) << "i = " << i;
  }
}

TYPED_TEST(ShaderIntersect, TangentRaysAndMisses) {
  using L = TypeParam;
  using R = typename L::Real;
  const R inf = std::numeric_limits<R>::infinity();
  const typename L::vec3 c = L::v3(0, 0, 0);
  // Exactly tangent at (1, 0, 0): the discriminant is exactly 0 and the double root is t = 5.
  EXPECT_EQ(L::intersect_sphere(L::ray({1, 0, -5}, {0, 0, 1}), c, R(1), R(0), inf), R(5));
  // Passing just outside misses, just inside hits.
  EXPECT_EQ(L::intersect_sphere(L::ray({1.001, 0, -5}, {0, 0, 1}), c, R(1), R(0), inf), L::no_hit());
  EXPECT_GT(L::intersect_sphere(L::ray({0.999, 0, -5}, {0, 0, 1}), c, R(1), R(0), inf), R(4.9));
  // Pointing away, or the whole sphere behind the origin.
  EXPECT_EQ(L::intersect_sphere(L::ray({0, 0, -5}, {0, 0, -1}), c, R(1), R(0), inf), L::no_hit());
  EXPECT_EQ(L::intersect_sphere(L::ray({0, 0, 5}, {0, 0, 1}), c, R(1), R(0), inf), L::no_hit());
  // Random rays whose line passes 1.001 to 3 radii from the centre never hit: the closest
  // point of the line is c + b e with e perpendicular to d, the origin 2 to 12 radii before it.
  Uniform u(3);
  for (int i = 0; i < 20000; ++i) {
    double r = std::pow(10.0, -2.0 + 5.0 * u());
    dvec3 d = u.unit_vector();
    dvec3 closest = r * (1.001 + 2.0 * u()) * perpendicular(d, u);
    dvec3 o = closest - r * (2.0 + 10.0 * u()) * d;
    ASSERT_EQ(L::intersect_sphere(L::ray(o, d), c, R(r), R(0), inf), L::no_hit()) << "i = " << i;
  }
}

// intersect_unit_sphere, which the trace shader uses (its directions are unit), against the
// general test on unit directions: rays from outside aimed inside the silhouette, rays from
// inside, and lines passing 1.001 to 3 radii from the centre. Both hit or both miss, and the
// hits agree to the rounding the two forms carry (64 eps of |o - c| + r, as above); the unit
// form's own near hit lies on the sphere to that tolerance.
TYPED_TEST(ShaderIntersect, UnitSphereTestAgreesWithTheGeneralOneOnUnitDirections) {
  using L = TypeParam;
  using R = typename L::Real;
  const R inf = std::numeric_limits<R>::infinity();
  EXPECT_EQ(L::intersect_unit_sphere(L::ray({0, 0, -5}, {0, 0, 1}), L::v3(0, 0, 0), R(1), R(0), inf), R(4));
  EXPECT_EQ(L::intersect_unit_sphere(L::ray({1, 0, -5}, {0, 0, 1}), L::v3(0, 0, 0), R(1), R(0), inf), R(5));
  EXPECT_EQ(L::intersect_unit_sphere(L::ray({0, 0, -5}, {0, 0, 1}), L::v3(0, 0, 0), R(1), R(4.5), inf), R(6));
  EXPECT_EQ(L::intersect_unit_sphere(L::ray({0, 0, -5}, {0, 0, 1}), L::v3(0, 0, 0), R(1), R(0), R(3.9)),
            L::no_hit());
  Uniform u(7);
  int hits = 0;
  for (int i = 0; i < 30000; ++i) {
    double r = std::pow(10.0, -2.0 + 5.0 * u());
    dvec3 c = (u.unit_vector() * 3.0) * r;
    dvec3 o, d;
    double dist;
    switch (i % 3) {
      case 0: {  // outside, aimed inside the silhouette
        dist = r * (1.5 + 8.5 * u());
        o = c + dist * u.unit_vector();
        dvec3 to_c = glm::normalize(c - o);
        d = glm::normalize(c + 0.95 * r * std::sqrt(u()) * perpendicular(to_c, u) - o);
        break;
      }
      case 1:  // inside
        o = c + 0.99 * r * u() * u.unit_vector();
        d = u.unit_vector();
        dist = glm::length(o - c);
        break;
      default: {  // the line misses
        d = u.unit_vector();
        o = c + r * (1.001 + 2.0 * u()) * perpendicular(d, u) - r * (2.0 + 10.0 * u()) * d;
        dist = glm::length(o - c);
      }
    }
    typename L::Ray ray = L::ray(o, d);
    R general = L::intersect_sphere(ray, L::v3(c), R(r), R(0), inf);
    R unit = L::intersect_unit_sphere(ray, L::v3(c), R(r), R(0), inf);
    double tol = 64.0 * L::kEps * (dist + r);
    if (i % 3 == 2) {
      ASSERT_EQ(unit, L::no_hit()) << "i = " << i;
      continue;
    }
    ASSERT_GT(unit, R(0)) << "miss, r = " << r << " i = " << i;
    ASSERT_GT(general, R(0)) << "i = " << i;
    ASSERT_NEAR(double(unit), double(general), tol) << "r = " << r << " i = " << i;
    dvec3 p = to_d(ray.origin) + double(unit) * to_d(ray.direction);
    ASSERT_NEAR(glm::length(p - c), r, tol) << "r = " << r << " i = " << i;
    ++hits;
  }
  EXPECT_EQ(hits, 20000);
}

// Origins 1e4 from a unit sphere. The inputs are the same float values in both builds, so the
// double result is exact to ~1e-12 and the difference is the float build's own error. With
// |o - c| = 1e4 the rounding of f = o - c, of b = f.d and of c = f.f - r^2 is a few float ulps
// of 1e4 (about 1e-3 each), and the discriminant, computed from the closest point of the line
// (error ~1e-3 on a quantity of order r^2 = 1), stays accurate because the test keeps the
// impact parameter below 0.9 r (sqrt(discriminant) >= 0.43). So t agrees to a few float ulps of
// t: the bound is 32 ulps (32 * 2^-23 relative, 0.04 at t = 1e4, i.e. 4% of the radius; the
// textbook b^2 - ac form loses everything here: b^2 and ac are 1e8 with float ulps of 8).
TEST(ShaderIntersect, FarAwayOriginsFloatAgreesWithDouble) {
  using F = FloatLib;
  using D = DoubleLib;
  Uniform u(4);
  const glm::vec3 c(3.0f, -2.0f, 7.0f);
  const float r = 1.0f;
  double worst = 0, worst_unit = 0;
  for (int i = 0; i < 20000; ++i) {
    dvec3 dir_from_c = u.unit_vector();
    glm::vec3 o = glm::vec3(dvec3(c) + 1e4 * dir_from_c);
    dvec3 to_c = glm::normalize(dvec3(c) - dvec3(o));
    double impact = 0.9 * std::sqrt(u());
    dvec3 target = dvec3(c) + impact * perpendicular(to_c, u);
    glm::vec3 d = glm::vec3(glm::normalize(target - dvec3(o)));
    float tf = F::intersect_sphere(F::Ray(o, d), c, r, 0.0f, 1e30f);
    double td = D::intersect_sphere(D::Ray(dvec3(o), dvec3(d)), dvec3(c), double(r), 0.0, 1e300);
    ASSERT_GT(td, 0.0);
    ASSERT_GT(tf, 0.0f) << "float misses, i = " << i;
    // The double hit is on the sphere (checks the double build itself).
    ASSERT_NEAR(glm::length(dvec3(o) + td * dvec3(d) - dvec3(c)), 1.0, 1e-8);
    double rel = std::abs(double(tf) - td) / td;
    worst = std::max(worst, rel);
    ASSERT_LE(rel, 32.0 * 0x1.0p-23) << "i = " << i << " tf = " << tf << " td = " << td;
    // The trace shader's form for unit directions: d is unit only to float rounding, which the
    // same bound covers.
    float tu = F::intersect_unit_sphere(F::Ray(o, d), c, r, 0.0f, 1e30f);
    double rel_unit = std::abs(double(tu) - td) / td;
    worst_unit = std::max(worst_unit, rel_unit);
    ASSERT_LE(rel_unit, 32.0 * 0x1.0p-23) << "i = " << i << " tu = " << tu << " td = " << td;
  }
  // Rays that pass 1.1 radii from the centre miss in both builds.
  for (int i = 0; i < 2000; ++i) {
    glm::vec3 o = glm::vec3(dvec3(c) + 1e4 * u.unit_vector());
    dvec3 to_c = glm::normalize(dvec3(c) - dvec3(o));
    dvec3 target = dvec3(c) + (1.1 + u()) * perpendicular(to_c, u);
    glm::vec3 d = glm::vec3(glm::normalize(target - dvec3(o)));
    EXPECT_EQ(F::intersect_sphere(F::Ray(o, d), c, r, 0.0f, 1e30f), F::no_hit());
    EXPECT_EQ(F::intersect_unit_sphere(F::Ray(o, d), c, r, 0.0f, 1e30f), F::no_hit());
    EXPECT_EQ(D::intersect_sphere(D::Ray(dvec3(o), dvec3(d)), dvec3(c), 1.0, 0.0, 1e300), D::no_hit());
  }
  RecordProperty("worst_difference_in_float_ulps_of_t", std::to_string(worst / 0x1.0p-23));
  RecordProperty("worst_unit_difference_in_float_ulps_of_t", std::to_string(worst_unit / 0x1.0p-23));
}

// Signed squared distance |o - c|^2 - r^2 and the far root of |o + t d - c| = r, in long
// double from the values as given (exact products of float inputs), as the reference.
long double outside_measure(dvec3 o, dvec3 c, double r) {
  long double fx = (long double)o.x - c.x, fy = (long double)o.y - c.y, fz = (long double)o.z - c.z;
  return fx * fx + fy * fy + fz * fz - (long double)r * r;
}
long double far_root(dvec3 o, dvec3 d, dvec3 c, double r) {
  long double fx = (long double)o.x - c.x, fy = (long double)o.y - c.y, fz = (long double)o.z - c.z;
  long double a = (long double)d.x * d.x + (long double)d.y * d.y + (long double)d.z * d.z;
  long double b = fx * d.x + fy * d.y + fz * d.z;
  long double disc = b * b - a * outside_measure(o, c, r);
  return (-b + std::sqrt(std::max(disc, 0.0L))) / a;
}

// A ray spawned as the trace shader spawns it (a unit direction, intersect_unit_sphere, the
// hit reprojected onto the sphere with
// sphere_hit_point, then offset_surface_point by the sphere's error scale) must not find the
// same surface again:
// leaving outwards (reflection off the outside, or refraction out of the inside) the offset
// origin is outside and the ray hits nothing; continuing inwards (refraction into the sphere,
// or reflection inside it) the origin is inside and the next hit is the far side of the sphere,
// not the point it started from. Hits come from rays traced in the same precision, so they
// carry its rounding errors. Centres lie at the origin and up to 10 radii (10 units for the
// small spheres) from it. tests/unit/hard_cases_test.cpp covers far wider ranges in float.
TYPED_TEST(ShaderIntersect, SpawnedRaysNeverRehitTheSameSphere) {
  using L = TypeParam;
  using R = typename L::Real;
  const R inf = std::numeric_limits<R>::infinity();
  Uniform u(5);
  int far_side_hits = 0;
  for (double r : {1e-2, 1e-1, 1.0, 10.0, 100.0, 1e3}) {
    for (int i = 0; i < 4000; ++i) {
      dvec3 c = to_d(L::v3(i % 4 == 0 ? dvec3(0) : u.unit_vector() * (10.0 * std::max(r, 1.0) * u())));
      bool from_inside = i % 2 == 1;
      dvec3 o = from_inside ? c + 0.9 * r * u() * u.unit_vector() : c + 3.0 * r * u.unit_vector();
      dvec3 d = from_inside ? u.unit_vector()
                            : glm::normalize(c + 0.99 * r * u.unit_vector() - o);
      typename L::Ray ray = L::ray(o, d);
      R t = L::intersect_unit_sphere(ray, L::v3(c), R(r), R(0), inf);
      ASSERT_GT(t, R(0));
      typename L::vec3 p = L::sphere_hit_point(ray, t, L::v3(c), R(r));
      typename L::vec3 n_out = glm::normalize(p - L::v3(c));
      R scale = L::sphere_error_scale(L::v3(c), R(r));
      // A random direction in each hemisphere, 1 in 8 of them grazing (cos = 1e-3 to 1e-2).
      Frame frame(to_d(n_out));
      double cos_theta = i % 8 == 0 ? 1e-3 + 9e-3 * u() : u();
      double phi = 2.0 * std::numbers::pi * u();

      typename L::Ray leaving(L::offset_surface_point(p, n_out, scale), L::v3(frame.to_world(cos_theta, phi)));
      ASSERT_GT(outside_measure(to_d(leaving.origin), c, r), 0.0L)
          << "offset origin not outside: r = " << r << " i = " << i;
      R t_out = L::intersect_unit_sphere(leaving, L::v3(c), R(r), R(0), inf);
      ASSERT_EQ(t_out, L::no_hit()) << "re-hit leaving the sphere: r = " << r << " i = " << i
                                    << " t = " << t_out;

      typename L::Ray entering(L::offset_surface_point(p, -n_out, scale), L::v3(frame.to_world(-cos_theta, phi)));
      ASSERT_LT(outside_measure(to_d(entering.origin), c, r), 0.0L)
          << "offset origin not inside: r = " << r << " i = " << i;
      R t_in = L::intersect_unit_sphere(entering, L::v3(c), R(r), R(0), inf);
      double expected = double(far_root(to_d(entering.origin), to_d(entering.direction), c, r));
      // The far side to the rounding of the coordinates (a few ulps of |c| + r, 64 allowed,
      // divided by cos(theta): a radial error e moves a chord's far end by e / cos(theta));
      // a self-hit would return t near 0 instead.
      double tol = 64.0 * L::kEps * (glm::length(c) + r) / cos_theta;
      ASSERT_NEAR(double(t_in), expected, tol) << "r = " << r << " i = " << i;
      ASSERT_GT(double(t_in), 0.5 * expected) << "self-hit entering: r = " << r << " i = " << i;
      ++far_side_hits;
    }
  }
  EXPECT_EQ(far_side_hits, 6 * 4000);
}

TYPED_TEST(ShaderIntersect, TriangleHitReturnsBarycentrics) {
  using L = TypeParam;
  using R = typename L::Real;
  const R inf = std::numeric_limits<R>::infinity();
  Uniform u(6);
  for (int i = 0; i < 20000; ++i) {
    dvec3 p0 = 5.0 * u.unit_vector(), p1 = 5.0 * u.unit_vector(), p2 = 5.0 * u.unit_vector();
    dvec3 n = glm::cross(p1 - p0, p2 - p0);
    if (glm::length(n) < 1.0) continue;  // skip slivers
    double b1 = u(), b2 = u();
    if (b1 + b2 > 1.0) b1 = 1.0 - b1, b2 = 1.0 - b2;
    dvec3 target = (1.0 - b1 - b2) * p0 + b1 * p1 + b2 * p2;
    dvec3 o = target + (2.0 + 10.0 * u()) * u.unit_vector();
    typename L::Ray ray = L::ray(o, glm::normalize(target - o));
    typename L::vec3 h = L::intersect_triangle(ray, L::v3(p0), L::v3(p1), L::v3(p2), R(0), inf);
    ASSERT_NE(h.x, L::no_hit()) << "i = " << i;
    double tol = 1e4 * L::kEps;  // barycentrics of a well-shaped triangle, |p| ~ 5
    EXPECT_NEAR(double(h.y), b1, tol);
    EXPECT_NEAR(double(h.z), b2, tol);
    EXPECT_NEAR(double(h.x), glm::length(target - o), tol * 10.0);
    // 1% outside each edge (one barycentric -0.01, the three summing to 1): miss.
    double w = u();
    for (dvec3 bary : {dvec3(-0.01, w, 1.01 - w), dvec3(w, -0.01, 1.01 - w), dvec3(w, 1.01 - w, -0.01)}) {
      dvec3 outside = bary.x * p0 + bary.y * p1 + bary.z * p2;
      typename L::Ray miss = L::ray(o, glm::normalize(outside - o));
      EXPECT_EQ(L::intersect_triangle(miss, L::v3(p0), L::v3(p1), L::v3(p2), R(0), inf).x, L::no_hit());
    }
  }
}

// docs/DESIGN.md §6: a quad is the triangles (p0, p1, p2) and (p1, p3, p2), p3 opposite p0, with
// texture coordinates interpolated over the triangle that was hit.
TYPED_TEST(ShaderIntersect, QuadTextureCoordinatesFollowTheDesignConvention) {
  using L = TypeParam;
  using R = typename L::Real;
  const R inf = std::numeric_limits<R>::infinity();
  // The ground quad of the docs/DESIGN.md example: u = (x + 10) / 4, v = (z + 10) / 4.
  const dvec3 p0(-10, 0, -10), p1(-10, 0, 10), p2(10, 0, -10), p3(10, 0, 10);
  const dvec2 uv0(0, 0), uv1(0, 5), uv2(5, 0), uv3(5, 5);
  EXPECT_NEAR(double(L::quad_normal(L::v3(p0), L::v3(p1), L::v3(p2)).y), 1.0, 4 * L::kEps);
  Uniform u(7);
  for (int i = 0; i < 2000; ++i) {
    double x = -10.0 + 20.0 * u(), z = -10.0 + 20.0 * u();
    double y = i % 2 == 0 ? 5.0 : -5.0;  // two-sided
    typename L::QuadHit hit = L::intersect_quad(
        L::ray({x, y, z}, {0, y > 0 ? -1 : 1, 0}), L::v3(p0), L::v3(p1), L::v3(p2), L::v3(p3),
        L::v2(uv0.x, uv0.y), L::v2(uv1.x, uv1.y), L::v2(uv2.x, uv2.y), L::v2(uv3.x, uv3.y), R(0), inf);
    ASSERT_NE(hit.t, L::no_hit()) << x << " " << z;
    EXPECT_NEAR(double(hit.t), 5.0, 1e-5);
    EXPECT_NEAR(double(hit.uv.x), (x + 10.0) / 4.0, 1e-4) << x << " " << z;
    EXPECT_NEAR(double(hit.uv.y), (z + 10.0) / 4.0, 1e-4) << x << " " << z;
  }
  // A non-affine assignment tells the triangles apart: uv3 only affects (p1, p3, p2), and
  // there each corner gets its own coordinates.
  const dvec2 q0(0, 0), q1(0, 1), q2(1, 0), q3(3, 2);
  auto uv_at = [&](dvec3 target) {
    return L::intersect_quad(L::ray(target + dvec3(0.1, 3.0, -0.2), dvec3(-0.1, -3.0, 0.2)),
                             L::v3(p0), L::v3(p1), L::v3(p2), L::v3(p3), L::v2(q0.x, q0.y),
                             L::v2(q1.x, q1.y), L::v2(q2.x, q2.y), L::v2(q3.x, q3.y), R(0), inf);
  };
  struct Case {
    dvec3 point;
    dvec2 uv;
  };
  for (Case k : {Case{(p0 + p1 + p2) / 3.0, (q0 + q1 + q2) / 3.0},
                 Case{(p1 + p3 + p2) / 3.0, (q1 + q3 + q2) / 3.0},
                 Case{0.9 * p3 + 0.05 * p1 + 0.05 * p2, 0.9 * q3 + 0.05 * q1 + 0.05 * q2},
                 Case{0.9 * p0 + 0.05 * p1 + 0.05 * p2, 0.9 * q0 + 0.05 * q1 + 0.05 * q2}}) {
    typename L::QuadHit hit = uv_at(k.point);
    ASSERT_NE(hit.t, L::no_hit());
    EXPECT_NEAR(double(hit.t), 1.0, 1e-4);  // the direction is the whole offset
    EXPECT_NEAR(double(hit.uv.x), k.uv.x, 1e-4);
    EXPECT_NEAR(double(hit.uv.y), k.uv.y, 1e-4);
  }
}

// Rays through points of the shared diagonal p1-p2 must hit one of the two triangles: no ray
// may slip through a crack between them. The quads are planar or folded along the diagonal,
// 0.1 to 100 units; the rays come from either side at 0.5 to 20 quad sizes and at least 3
// degrees off the plane (at grazing angles the rounding of the ray itself, eps * distance /
// sin(angle), could move its exact crossing point off the quad near a corner), through
// points 1% to 99% along the diagonal, seeing both triangles from the same side (otherwise the
// fold is a silhouette, which a ray may graze and miss).
TYPED_TEST(ShaderIntersect, QuadDiagonalHasNoCrack) {
  using L = TypeParam;
  using R = typename L::Real;
  const R inf = std::numeric_limits<R>::infinity();
  Uniform u(8);
  int misses = 0, rays = 0;
  for (int q = 0; q < 200; ++q) {
    double scale = std::pow(10.0, -1.0 + 3.0 * u());
    dvec3 p0 = scale * 3.0 * u.unit_vector();
    dvec3 e1 = scale * u.unit_vector(), e2 = scale * u.unit_vector();
    if (glm::length(glm::cross(e1, e2)) < 0.2 * scale * scale) continue;
    dvec3 n = glm::normalize(glm::cross(e1, e2));
    double fold = q % 2 == 0 ? 0.0 : scale * (u() - 0.5);
    dvec3 p1 = p0 + e1, p2 = p0 + e2;
    dvec3 p3 = p0 + (0.7 + 0.6 * u()) * e1 + (0.7 + 0.6 * u()) * e2 + fold * n;
    dvec3 na = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    dvec3 nb = glm::normalize(glm::cross(p3 - p1, p2 - p1));
    typename L::vec3 f0 = L::v3(p0), f1 = L::v3(p1), f2 = L::v3(p2), f3 = L::v3(p3);
    typename L::vec2 zero = L::v2(0, 0);
    for (int i = 0; i < 1000; ++i) {
      double s = 0.01 + 0.98 * u();
      dvec3 target = to_d(f1) + s * (to_d(f2) - to_d(f1));
      // Both triangles seen from the same side (else a folded quad's diagonal is a silhouette
      // that a ray may graze and miss).
      dvec3 w = u.unit_vector();
      while (!(glm::dot(w, na) * glm::dot(w, nb) > 0.0 && std::abs(glm::dot(w, na)) >= 0.05 &&
               std::abs(glm::dot(w, nb)) >= 0.05)) {
        w = u.unit_vector();
      }
      dvec3 o = target + scale * (0.5 + 20.0 * u()) * w;
      typename L::Ray ray = L::ray(o, glm::normalize(target - o));
      typename L::QuadHit hit = L::intersect_quad(ray, f0, f1, f2, f3, zero, zero, zero, zero, R(0), inf);
      ++rays;
      if (hit.t == L::no_hit()) ++misses;
    }
  }
  EXPECT_EQ(misses, 0) << "of " << rays << " rays through the shared edge";
}

// Quads need not be planar (docs/DESIGN.md §6 only rejects zero area): a folded quad can be
// crossed twice, and the nearer triangle must win whichever one it is.
TYPED_TEST(ShaderIntersect, FoldedQuadReturnsTheNearerTriangle) {
  using L = TypeParam;
  using R = typename L::Real;
  const R inf = std::numeric_limits<R>::infinity();
  // (p0, p1, p2) lies in y = 0; (p1, p3, p2) in the plane y = 2 (x + z - 1).
  const dvec3 p0(0, 0, 0), p1(0, 0, 1), p2(1, 0, 0), p3(1, 2, 1);
  const dvec3 low(0.1, -0.5, 0.1), high(0.9, 1.0, 0.9);
  typename L::vec2 uv0 = L::v2(0, 0), uv1 = L::v2(0, 1), uv2 = L::v2(1, 0), uv3 = L::v2(1, 1);
  auto hit = [&](dvec3 o, dvec3 d) {
    return L::intersect_quad(L::ray(o, d), L::v3(p0), L::v3(p1), L::v3(p2), L::v3(p3), uv0, uv1,
                             uv2, uv3, R(0), inf);
  };
  // Upwards from below: y = 0 first at s = 1/3, then the fold at s = 11/17.
  typename L::QuadHit up = hit(low, high - low);
  EXPECT_NEAR(double(up.t), 1.0 / 3.0, 1e-5);
  // Downwards from above: the fold first at s = 6/17 (1 - 11/17), then y = 0 at s = 2/3.
  typename L::QuadHit down = hit(high, low - high);
  EXPECT_NEAR(double(down.t), 6.0 / 17.0, 1e-5);
}

// The planar test (intersect_planar_quad, for scenes whose quads all are planar and convex)
// against the two-triangle one on planar convex quads: parallelograms and general convex
// quads (p3 moved within the plane, keeping every corner convex), 0.1 to 100 units, rays from
// either side at least 3 degrees off the plane through points around the quad. Both must agree
// on hit or miss wherever the point is more than 1e-4 of the size from the boundary (at the
// boundary either answer is right), and on t to 8 epsilons of the distance from the ray's
// origin to p0 and the quad's size, over the cosine of the incidence (the rounding of p0 - o
// and of the corners moves the plane by that much along the ray).
TYPED_TEST(ShaderIntersect, PlanarQuadAgreesWithTheTwoTriangles) {
  using L = TypeParam;
  using R = typename L::Real;
  const R inf = std::numeric_limits<R>::infinity();
  Uniform u(10);
  long rays = 0, hits = 0, disagreements = 0;
  double worst_t = 0.0;
  const typename L::vec2 zero = L::v2(0, 0);
  for (int q = 0; q < 200; ++q) {
    const double scale = std::pow(10.0, -1.0 + 3.0 * u());
    const dvec3 e1 = scale * u.unit_vector(), e2 = scale * u.unit_vector();
    if (glm::length(glm::cross(e1, e2)) < 0.2 * scale * scale) continue;
    const dvec3 p0 = scale * 2.0 * u.unit_vector();
    // (a, b) of p3 = p0 + a e1 + b e2: (1, 1) is the parallelogram; a, b > 0 and a + b > 1
    // keep the quad convex.
    const double a = q % 2 == 0 ? 1.0 : 0.6 + 0.8 * u(), b = q % 2 == 0 ? 1.0 : 0.6 + 0.8 * u();
    const typename L::vec3 f0 = L::v3(p0), f1 = L::v3(p0 + e1), f2 = L::v3(p0 + e2),
                           f3 = L::v3(p0 + a * e1 + b * e2);
    const dvec3 n = glm::normalize(glm::cross(e1, e2));
    // Boundary p0 p1 p3 p2 in the plane's coordinates (x along e1, y along the in-plane normal).
    const dvec3 ex = glm::normalize(e1), ey = glm::cross(n, ex);
    auto plane2 = [&](dvec3 p) { return dvec2(glm::dot(p - p0, ex), glm::dot(p - p0, ey)); };
    const dvec2 boundary[4] = {plane2(to_d(f0)), plane2(to_d(f1)), plane2(to_d(f3)), plane2(to_d(f2))};
    for (int i = 0; i < 500; ++i) {
      const dvec3 target = p0 + (-0.3 + 1.8 * u()) * e1 + (-0.3 + 1.8 * u()) * e2;
      // Signed distance to each boundary line (positive inside, the boundary turns left).
      const dvec2 t2 = plane2(target);
      double inside = inf;
      for (int k = 0; k < 4; ++k) {
        const dvec2 from = boundary[k], along = glm::normalize(boundary[(k + 1) % 4] - from);
        inside = std::min(inside, along.x * (t2.y - from.y) - along.y * (t2.x - from.x));
      }
      if (std::abs(inside) < 1e-4 * scale) continue;
      dvec3 w = u.unit_vector();
      if (std::abs(glm::dot(w, n)) < 0.05) continue;
      const dvec3 o = target + scale * (0.5 + 20.0 * u()) * w;
      const typename L::Ray ray = L::ray(o, glm::normalize(target - o));
      const R t_planar = L::intersect_planar_quad(ray, f0, f1, f2, f3, L::v3(n), R(0), inf);
      const R t_quad = L::intersect_quad(ray, f0, f1, f2, f3, zero, zero, zero, zero, R(0), inf).t;
      ++rays;
      disagreements += (t_planar == L::no_hit()) != (inside < 0.0);
      disagreements += (t_quad == L::no_hit()) != (inside < 0.0);
      if (t_planar != L::no_hit() && t_quad != L::no_hit()) {
        ++hits;
        const double cos_theta = std::abs(glm::dot(glm::normalize(target - o), n));
        const double bound = 8.0 * double(L::kEps) * (glm::length(p0 - o) + scale) / cos_theta;
        worst_t = std::max(worst_t, std::abs(double(t_planar) - double(t_quad)) / bound);
      }
    }
  }
  this->RecordProperty("worst_t_difference_over_bound", std::to_string(worst_t));
  EXPECT_GT(rays, 40000);
  EXPECT_GT(hits, 10000);
  EXPECT_EQ(disagreements, 0) << "of " << rays << " rays";
  EXPECT_LT(worst_t, 1.0);
}

TYPED_TEST(ShaderIntersect, ParallelRaysMiss) {
  using L = TypeParam;
  using R = typename L::Real;
  const R inf = std::numeric_limits<R>::infinity();
  const dvec3 p0(-1, 0, -1), p1(-1, 0, 1), p2(1, 0, -1), p3(1, 0, 1);
  typename L::vec2 zero = L::v2(0, 0);
  auto quad = [&](dvec3 o, dvec3 d) {
    return L::intersect_quad(L::ray(o, d), L::v3(p0), L::v3(p1), L::v3(p2), L::v3(p3), zero, zero,
                             zero, zero, R(0), inf).t;
  };
  auto planar = [&](dvec3 o, dvec3 d) {
    return L::intersect_planar_quad(L::ray(o, d), L::v3(p0), L::v3(p1), L::v3(p2), L::v3(p3),
                                    L::v3(0, 1, 0), R(0), inf);
  };
  Uniform u(9);
  for (int i = 0; i < 1000; ++i) {
    double phi = 2.0 * std::numbers::pi * u();
    dvec3 d(std::cos(phi), 0.0, std::sin(phi));  // exactly in the plane y = 0
    dvec3 o(-3.0 + 6.0 * u(), 0.0, -3.0 + 6.0 * u());
    EXPECT_EQ(quad(o, d), L::no_hit()) << "in the plane";
    EXPECT_EQ(planar(o, d), L::no_hit()) << "in the plane";
    EXPECT_EQ(planar(o + dvec3(0, 0.01 + u(), 0), d), L::no_hit()) << "above the plane";
    EXPECT_EQ(quad(o + dvec3(0, 0.01 + u(), 0), d), L::no_hit()) << "above the plane";
    EXPECT_EQ(quad(o - dvec3(0, 0.01 + u(), 0), d), L::no_hit()) << "below the plane";
  }
  // Along the diagonal itself, and along the edges.
  EXPECT_EQ(quad(p1 + (p1 - p2), glm::normalize(p2 - p1)), L::no_hit());
  EXPECT_EQ(quad(p0 - (p1 - p0), glm::normalize(p1 - p0)), L::no_hit());
  // A tilted quad with rays parallel to it 1e-3 above its plane.
  const dvec3 a0(0.3, -1, 2), e1(1.5, 0.5, -0.2), e2(-0.4, 1.2, 0.9);
  const dvec3 nrm = glm::normalize(glm::cross(e1, e2));
  for (int i = 0; i < 1000; ++i) {
    dvec3 in_plane = glm::normalize((u() - 0.5) * e1 + (u() - 0.5) * e2);
    dvec3 o = a0 + 3.0 * (u() - 0.5) * e1 + 3.0 * (u() - 0.5) * e2 + 1e-3 * nrm;
    typename L::QuadHit hit =
        L::intersect_quad(L::ray(o, in_plane), L::v3(a0), L::v3(a0 + e1), L::v3(a0 + e2),
                          L::v3(a0 + e1 + e2), zero, zero, zero, zero, R(0), inf);
    EXPECT_EQ(hit.t, L::no_hit());
    EXPECT_EQ(L::intersect_planar_quad(L::ray(o, in_plane), L::v3(a0), L::v3(a0 + e1), L::v3(a0 + e2),
                                       L::v3(a0 + e1 + e2), L::v3(nrm), R(0), inf),
              L::no_hit());
  }
}

}  // namespace
}  // namespace glint::shader_test
