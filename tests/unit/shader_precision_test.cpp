// Numerical stability on hard cases, on the CPU: the shared shader maths of shaders/lib
// compiled as C++ (float unless said otherwise, as the GPU runs it). `ctest -R hard_` runs
// these with the rendered ones (tests/gl/render_precision_test.cpp) and the loader's
// (hard_Load in malformed_input_test.cpp).
// Rays are intersected with spheres as the trace shader intersects them: every direction it
// spawns is unit, so intersect_unit_sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/quad_shape.h"
#include "shader_test_util.h"

namespace glint::shader_test {
namespace {

using glm::dvec2;
using glm::dvec3;
using glm::vec2;
using glm::vec3;
namespace F = ::glint::gpu;

// The renderer's first ray offset, kept only to count how often it failed (Wachter and Binder,
// Ray Tracing Gems ch. 6: 256 float ulps of p along n, 1/65536 near the origin). It ignores the
// shape's size and the error of o + t d, which is what the hard cases below exposed.
vec3 legacy_offset_ray_origin(vec3 p, vec3 n) {
  auto shift = [](float x, float nx) {
    if (std::abs(x) < 1.0f / 32.0f) return x + nx / 65536.0f;
    int bits = glm::floatBitsToInt(x);
    int delta = int(256.0f * nx);
    return glm::intBitsToFloat(bits + (x < 0.0f ? -delta : delta));
  };
  return vec3(shift(p.x, n.x), shift(p.y, n.y), shift(p.z, n.z));
}
constexpr float kInf = std::numeric_limits<float>::infinity();

// |o - c|^2 - r^2 in long double from the float values as given: > 0 outside, < 0 inside.
long double outside_measure(vec3 o, vec3 c, float r) {
  long double s = 0;
  for (int i = 0; i < 3; ++i) {
    long double f = (long double)o[i] - (long double)c[i];
    s += f * f;
  }
  return s - (long double)r * r;
}

// A random direction with cos(theta) in the given range about n, in float.
vec3 direction_about(dvec3 n, double cos_theta, Uniform& u) {
  Frame frame(n);
  return vec3(frame.to_world(cos_theta, 2.0 * std::numbers::pi * u()));
}

// Radii 1e-4 to 1e4, shapes centred at 0 to 1e6 from the origin, with radius / |centre| at
// least 1e-4 (the tiny-far-sphere ratio; below it a float sphere is a handful of ulps wide:
// r = 1e-4 at 1e6 is 1/600 of an ulp there, and no offset can work).
struct ShapeCase {
  double size;
  double distance;
};
std::vector<ShapeCase> shape_cases() {
  std::vector<ShapeCase> cases;
  for (double size = 1e-4; size <= 1.01e4; size *= 10.0)
    for (double distance : {0.0, 1.0, 1e2, 1e4, 1e6})
      if (size >= 1e-4 * distance * 0.999) cases.push_back({size, distance});
  return cases;
}

// Re-intersection, spheres: a ray spawned from a sphere hit (the hit traced in float from
// near, 1.5 to 10 radii, or far, 1e3 to 1e4 radii, as a distant camera) never finds the same
// surface again. Leaving outwards: no hit at all (a sphere is convex). Entering: the far side,
// at more than half the exact chord from the spawned origin (a self-hit is t ~ 0). 1 in 8 of the
// spawned directions graze (cos 1e-4 to 1e-2). The trace shader spawns rays exactly this way:
// sphere_hit_point (reprojection) and offset_surface_point with sphere_error_scale. The old
// way (o + t d, legacy_offset_ray_origin: 256 ulps of p, ignoring the shape's size) is counted too.
TEST(hard_Reintersection, SpawnedRaysNeverRehitASphereFloat) {
  Uniform u(101);
  long failures = 0, legacy_failures = 0, rays = 0;
  std::string first_failure;
  for (ShapeCase sc : shape_cases()) {
    const double r = sc.size;
    for (int i = 0; i < 2000; ++i) {
      const vec3 c = vec3(sc.distance * u.unit_vector());
      const float rf = float(r);
      const double from = i % 2 == 0 ? 1.5 + 8.5 * u() : 1e3 + 9e3 * u();
      const vec3 o = vec3(dvec3(c) + from * r * u.unit_vector());
      const dvec3 to_c = glm::normalize(dvec3(c) - dvec3(o));
      const dvec3 target = dvec3(c) + 0.9 * r * std::sqrt(u()) * Frame(to_c).to_world(0.0, 6.3 * u());
      const F::Ray ray(o, vec3(glm::normalize(target - dvec3(o))));
      const float t = F::intersect_unit_sphere(ray, c, rf, 0.0f, kInf);
      if (t == F::NO_HIT) continue;  // the target rounded off a tiny far sphere: not this test
      const bool grazing = i % 8 < 2;
      const double cos_theta = grazing ? std::pow(10.0, -4.0 + 2.0 * u()) : 0.01 + 0.99 * u();
      for (int legacy = 0; legacy < 2; ++legacy) {
        vec3 p = legacy ? ray.origin + t * ray.direction : F::sphere_hit_point(ray, t, c, rf);
        vec3 n = glm::normalize(p - c);
        auto spawn = [&](vec3 side) {
          return legacy ? legacy_offset_ray_origin(p, side)
                        : F::offset_surface_point(p, side, F::sphere_error_scale(c, rf));
        };
        const vec3 d_out = direction_about(dvec3(n), cos_theta, u);
        const F::Ray out(spawn(n), d_out);
        bool bad = F::intersect_unit_sphere(out, c, rf, 0.0f, kInf) != F::NO_HIT;
        const F::Ray in(spawn(-n), direction_about(dvec3(n), -cos_theta, u));
        const float t_in = F::intersect_unit_sphere(in, c, rf, 0.0f, kInf);
        // The exact chord from the spawned origin: -2 (f.d) for an origin on the sphere.
        const long double chord =
            -2.0L * ((long double)(in.origin.x - c.x) * in.direction.x +
                     (long double)(in.origin.y - c.y) * in.direction.y +
                     (long double)(in.origin.z - c.z) * in.direction.z);
        bad = bad || outside_measure(in.origin, c, rf) >= 0 || t_in == F::NO_HIT ||
              (long double)t_in < 0.5L * chord;
        if (legacy) {
          legacy_failures += bad;
        } else if (bad) {
          if (failures++ == 0)
            first_failure = "r = " + std::to_string(r) + " |c| = " + std::to_string(sc.distance) +
                            " cos = " + std::to_string(cos_theta);
        }
      }
      ++rays;
    }
  }
  RecordProperty("rays", std::to_string(rays));
  RecordProperty("legacy_failures", std::to_string(legacy_failures));
  std::printf("spheres: %ld hits, %ld failures with the old offset\n", rays, legacy_failures);
  EXPECT_GT(rays, 60000);
  EXPECT_EQ(failures, 0) << "first: " << first_failure;
}

// Re-intersection, quads: the same for a random parallelogram of size 1e-4 to 1e4 whose
// corner lies 0 to 1e6 from the origin, hit from near or far. A planar quad is convex: a ray
// spawned from it on either side (reflected or passing through) never hits it again.
TEST(hard_Reintersection, SpawnedRaysNeverRehitAQuadFloat) {
  Uniform u(102);
  long failures = 0, legacy_failures = 0, rays = 0;
  std::string first_failure;
  const vec2 zero(0.0f);
  for (ShapeCase sc : shape_cases()) {
    const double s = sc.size;
    for (int i = 0; i < 2000; ++i) {
      const dvec3 e1 = s * u.unit_vector(), e2 = s * u.unit_vector();
      if (glm::length(glm::cross(e1, e2)) < 0.1 * s * s) continue;
      const vec3 p0 = vec3(sc.distance * u.unit_vector());
      const vec3 p1 = vec3(dvec3(p0) + e1), p2 = vec3(dvec3(p0) + e2), p3 = vec3(dvec3(p0) + e1 + e2);
      const dvec3 n = glm::normalize(glm::cross(dvec3(p1) - dvec3(p0), dvec3(p2) - dvec3(p0)));
      const dvec3 target = dvec3(p0) + (0.02 + 0.96 * u()) * e1 + (0.02 + 0.96 * u()) * e2;
      const double from = i % 2 == 0 ? 1.5 + 8.5 * u() : 1e3 + 9e3 * u();
      dvec3 w = u.unit_vector();
      if (std::abs(glm::dot(w, n)) < 0.05) continue;
      const vec3 o = vec3(target + from * s * w);
      const F::Ray ray(o, vec3(glm::normalize(target - dvec3(o))));
      const F::QuadHit hit = F::intersect_quad(ray, p0, p1, p2, p3, zero, zero, zero, zero, 0.0f, kInf);
      if (hit.t == F::NO_HIT) continue;
      const vec3 nf = vec3(glm::dot(w, n) > 0 ? n : -n);  // towards the incoming ray
      const bool grazing = i % 8 < 2;
      const double cos_theta = grazing ? std::pow(10.0, -4.0 + 2.0 * u()) : 0.01 + 0.99 * u();
      for (int legacy = 0; legacy < 2; ++legacy) {
        const vec3 p = legacy ? ray.origin + hit.t * ray.direction : hit.position;
        auto spawn = [&](vec3 side) {
          return legacy ? legacy_offset_ray_origin(p, side)
                        : F::offset_surface_point(p, side, F::quad_error_scale(p0, p1, p2, p3));
        };
        bool bad = false;
        for (double side : {1.0, -1.0}) {
          const F::Ray next(spawn(float(side) * nf), direction_about(side * dvec3(nf), cos_theta, u));
          bad = bad || F::intersect_quad(next, p0, p1, p2, p3, zero, zero, zero, zero, 0.0f, kInf).t != F::NO_HIT;
        }
        if (legacy) {
          legacy_failures += bad;
        } else if (bad) {
          if (failures++ == 0)
            first_failure = "size = " + std::to_string(s) + " |p0| = " + std::to_string(sc.distance) +
                            " cos = " + std::to_string(cos_theta);
        }
      }
      ++rays;
    }
  }
  RecordProperty("rays", std::to_string(rays));
  RecordProperty("legacy_failures", std::to_string(legacy_failures));
  std::printf("quads: %ld hits, %ld failures with the old offset\n", rays, legacy_failures);
  EXPECT_GT(rays, 40000);
  EXPECT_EQ(failures, 0) << "first: " << first_failure;
}

// The same for the planar test (intersect_planar_quad), on the quads a scene may give it
// (quad_is_planar_convex): its t comes from the plane of (p0, p1, p2) and a normal rounded to
// float, the spawned point from intersect_quad's barycentrics (as the trace shader's hit record
// does). Axis-aligned rectangles (planar in float wherever they lie) and parallelograms turned
// at random (kept when their rounded corners pass), at the sizes and distances above.
TEST(hard_Reintersection, SpawnedRaysNeverRehitAPlanarQuadFloat) {
  Uniform u(109);
  long failures = 0, rays = 0, turned = 0;
  std::string first_failure;
  const vec2 zero(0.0f);
  for (ShapeCase sc : shape_cases()) {
    const double s = sc.size;
    for (int i = 0; i < 2000; ++i) {
      const bool aligned = i % 2 == 0;
      dvec3 e1 = s * u.unit_vector(), e2 = s * u.unit_vector();
      if (aligned) {
        const int axis = i % 3;
        e1 = dvec3(0.0);
        e2 = dvec3(0.0);
        e1[axis] = s * (0.5 + u());
        e2[(axis + 1) % 3] = s * (0.5 + u());
      }
      if (glm::length(glm::cross(e1, e2)) < 0.1 * s * s) continue;
      const vec3 p0 = vec3(sc.distance * u.unit_vector());
      const vec3 p1 = vec3(dvec3(p0) + e1), p2 = vec3(dvec3(p0) + e2), p3 = vec3(dvec3(p0) + e1 + e2);
      if (!quad_is_planar_convex({p0, p1, p2, p3})) continue;
      turned += !aligned;
      const dvec3 n = glm::normalize(glm::cross(dvec3(p1) - dvec3(p0), dvec3(p2) - dvec3(p0)));
      const vec3 nf32 = vec3(n);
      const dvec3 target = dvec3(p0) + (0.02 + 0.96 * u()) * (dvec3(p1) - dvec3(p0)) +
                           (0.02 + 0.96 * u()) * (dvec3(p2) - dvec3(p0));
      const double from = i % 4 < 2 ? 1.5 + 8.5 * u() : 1e3 + 9e3 * u();
      dvec3 w = u.unit_vector();
      if (std::abs(glm::dot(w, n)) < 0.05) continue;
      const vec3 o = vec3(target + from * s * w);
      const F::Ray ray(o, vec3(glm::normalize(target - dvec3(o))));
      if (F::intersect_planar_quad(ray, p0, p1, p2, p3, nf32, 0.0f, kInf) == F::NO_HIT) continue;
      const F::QuadHit hit = F::intersect_quad(ray, p0, p1, p2, p3, zero, zero, zero, zero, 0.0f, kInf);
      if (hit.t == F::NO_HIT) continue;
      const vec3 nf = vec3(glm::dot(w, n) > 0 ? n : -n);
      const double cos_theta = i % 8 < 2 ? std::pow(10.0, -4.0 + 2.0 * u()) : 0.01 + 0.99 * u();
      for (double side : {1.0, -1.0}) {
        const vec3 origin = F::offset_surface_point(hit.position, float(side) * nf, F::quad_error_scale(p0, p1, p2, p3));
        const F::Ray next(origin, direction_about(side * dvec3(nf), cos_theta, u));
        if (F::intersect_planar_quad(next, p0, p1, p2, p3, nf32, 0.0f, kInf) != F::NO_HIT && failures++ == 0)
          first_failure = "size = " + std::to_string(s) + " |p0| = " + std::to_string(sc.distance) +
                          " cos = " + std::to_string(cos_theta);
      }
      ++rays;
    }
  }
  RecordProperty("rays", std::to_string(rays));
  std::printf("planar quads: %ld hits (%ld on turned parallelograms)\n", rays, turned);
  EXPECT_GT(rays, 20000);
  EXPECT_GT(turned, 2000);
  EXPECT_EQ(failures, 0) << "first: " << first_failure;
}

// The huge-sphere floor: radius 1e5, centre (0, -1e5, 0), so its top is the plane y = 0 to
// within x^2 / 2e5. Rays from a camera 1 to 3 units above look down at 2 to 60 degrees below
// the horizon onto points within 10 units. The reprojected hit point must lie within the
// float rounding of the sphere (its coordinates are only known to ulps of 1e5: 0.0078) and a
// matte bounce spawned from it must escape: no acne. The error of the plain o + t d is
// reported for comparison (t's rounding is eps |o - c| / cos: up to 0.1 units).
TEST(hard_Intersection, HugeSphereFloorHasNoAcneFloat) {
  Uniform u(103);
  const vec3 c(0.0f, -1e5f, 0.0f);
  const float r = 1e5f;
  long escapes = 0, rays = 0;
  double worst_plain = 0, worst_projected = 0;
  for (int i = 0; i < 20000; ++i) {
    const vec3 o(float(-5 + 10 * u()), float(1 + 2 * u()), float(-5 + 10 * u()));
    const double below = glm::radians(2.0 + 58.0 * u()), phi = 6.3 * u();
    const vec3 d(float(std::cos(below) * std::cos(phi)), float(-std::sin(below)), float(std::cos(below) * std::sin(phi)));
    const F::Ray ray(o, d);
    const float t = F::intersect_unit_sphere(ray, c, r, 0.0f, kInf);
    ASSERT_NE(t, F::NO_HIT);
    const vec3 plain = o + t * d, p = F::sphere_hit_point(ray, t, c, r);
    worst_plain = std::max(worst_plain, std::abs(double(std::sqrt(std::abs(outside_measure(plain, c, r)) + (long double)r * r) - r)));
    worst_projected = std::max(worst_projected, std::abs(double(std::sqrt(std::abs(outside_measure(p, c, r)) + (long double)r * r) - r)));
    const vec3 n = glm::normalize(p - c);
    const double cos_theta = i % 4 == 0 ? std::pow(10.0, -3.0 + 2.0 * u()) : u();
    const F::Ray bounce(F::offset_surface_point(p, n, F::sphere_error_scale(c, r)), direction_about(dvec3(n), cos_theta, u));
    escapes += F::intersect_unit_sphere(bounce, c, r, 0.0f, kInf) == F::NO_HIT;
    ++rays;
  }
  RecordProperty("worst_radial_error_plain", std::to_string(worst_plain));
  RecordProperty("worst_radial_error_reprojected", std::to_string(worst_projected));
  std::printf("huge sphere: radial error of o + t d up to %g, reprojected up to %g\n", worst_plain, worst_projected);
  EXPECT_LT(worst_projected, 4.0 * 0x1.0p-23 * 1e5);  // a few ulps of max(|c|, r)
  EXPECT_EQ(escapes, rays);
}

// A tiny far sphere (radius / distance = 1e-4, distances 1 to 1e4, cameras at the origin or
// up to `distance` from it): every ray aimed within 0.95 of the radius of its centre hits its
// near side; rays aimed 1.05 radii off miss.
TEST(hard_Intersection, TinyFarSphereIsHitByRaysAimedAtIt) {
  Uniform u(104);
  long misses = 0, false_hits = 0, rays = 0;
  for (double distance : {1.0, 10.0, 1e2, 1e3, 1e4}) {
    const double r = 1e-4 * distance;
    for (int i = 0; i < 5000; ++i) {
      const dvec3 o = (i % 2 == 0 ? 0.0 : distance * u()) * u.unit_vector();
      const dvec3 axis = u.unit_vector();
      const vec3 c = vec3(o + distance * axis);
      const vec3 of = vec3(o);
      const dvec3 to_c = glm::normalize(dvec3(c) - dvec3(of));
      const dvec3 side = Frame(to_c).to_world(0.0, 6.3 * u());
      const double impact = 0.95 * std::sqrt(u());
      const F::Ray hit_ray(of, vec3(glm::normalize(dvec3(c) + impact * r * side - dvec3(of))));
      const float t = F::intersect_unit_sphere(hit_ray, c, float(r), 0.0f, kInf);
      misses += t == F::NO_HIT;
      if (t != F::NO_HIT) {
        const vec3 p = F::sphere_hit_point(hit_ray, t, c, float(r));
        // The near side: the hit faces the camera.
        misses += glm::dot(dvec3(p) - dvec3(c), dvec3(hit_ray.direction)) > 0;
      }
      const F::Ray miss_ray(of, vec3(glm::normalize(dvec3(c) + 1.05 * r * side - dvec3(of))));
      false_hits += F::intersect_unit_sphere(miss_ray, c, float(r), 0.0f, kInf) != F::NO_HIT;
      ++rays;
    }
  }
  EXPECT_EQ(misses, 0) << "of " << rays;
  EXPECT_EQ(false_hits, 0) << "of " << rays;
}

// Two quads sharing an edge (corners bit-identical), at sizes 1e-2 to 1e2, both the same and
// opposite corner orders along the edge, coplanar or folded up to 60 degrees: rays through
// points of the shared edge, from the side both quads face (as in a closed box), hit one of
// them. No crack lets light through.
TEST(hard_Intersection, TwoQuadsSharingAnEdgeHaveNoCrack) {
  Uniform u(105);
  long misses = 0, planar_misses = 0, rays = 0;
  const vec2 z(0.0f);
  for (int q = 0; q < 400; ++q) {
    const double s = std::pow(10.0, -2.0 + 4.0 * u());
    const dvec3 a = s * 5.0 * u.unit_vector();
    const dvec3 e = s * u.unit_vector();  // the shared edge a -> a + e
    const dvec3 side_a = s * glm::normalize(glm::cross(e, u.unit_vector()));
    const dvec3 nrm = glm::normalize(glm::cross(e, side_a));
    const double fold = q % 3 == 0 ? 0.0 : glm::radians(60.0) * (u() - 0.5) * 2.0;
    // side_b continues the plane of A across the edge, rotated about the edge by `fold`.
    const dvec3 side_b = -std::cos(fold) * side_a + std::sin(fold) * glm::length(side_a) * nrm;
    const vec3 e0 = vec3(a), e1 = vec3(a + e);
    // Quad A: p0 = e0 + side_a, p1 = e1 + side_a, p2 = e0, p3 = e1 (shared edge p2-p3).
    const vec3 A[4] = {vec3(a + side_a), vec3(a + e + side_a), e0, e1};
    // Quad B shares it as p0-p1 (same order) or p1-p0 (reversed).
    const bool reversed = q % 2 == 1;
    const vec3 B[4] = {reversed ? e1 : e0, reversed ? e0 : e1, vec3((reversed ? a + e : a) + side_b),
                       vec3((reversed ? a : a + e) + side_b)};
    const dvec3 na = glm::normalize(glm::cross(dvec3(A[1]) - dvec3(A[0]), dvec3(A[2]) - dvec3(A[0])));
    const dvec3 nb = glm::normalize(glm::cross(dvec3(B[1]) - dvec3(B[0]), dvec3(B[2]) - dvec3(B[0])));
    // The side both quads face (normals up to sign): inside the fold's concave side.
    const dvec3 up_a = glm::dot(na, nrm) > 0 ? na : -na, up_b = glm::dot(nb, nrm) > 0 ? nb : -nb;
    for (int i = 0; i < 500; ++i) {
      const dvec3 target = dvec3(e0) + (0.01 + 0.98 * u()) * (dvec3(e1) - dvec3(e0));
      dvec3 w = u.unit_vector();
      const double sign = fold >= 0 ? 1.0 : -1.0;  // approach from the concave side
      if (glm::dot(w, sign * up_a) < 0.05 || glm::dot(w, sign * up_b) < 0.05) continue;
      const vec3 o = vec3(target + s * (0.5 + 20.0 * u()) * w);
      const F::Ray ray(o, vec3(glm::normalize(target - dvec3(o))));
      const float ta = F::intersect_quad(ray, A[0], A[1], A[2], A[3], z, z, z, z, 0.0f, kInf).t;
      const float tb = F::intersect_quad(ray, B[0], B[1], B[2], B[3], z, z, z, z, 0.0f, kInf).t;
      misses += ta == F::NO_HIT && tb == F::NO_HIT;
      // The planar test takes the same edge volumes: no crack either (its t uses each quad's
      // own plane; these quads are planar up to the rounding of their corners).
      const float pa = F::intersect_planar_quad(ray, A[0], A[1], A[2], A[3], vec3(na), 0.0f, kInf);
      const float pb = F::intersect_planar_quad(ray, B[0], B[1], B[2], B[3], vec3(nb), 0.0f, kInf);
      planar_misses += pa == F::NO_HIT && pb == F::NO_HIT;
      ++rays;
    }
  }
  EXPECT_GT(rays, 50000);
  EXPECT_EQ(misses, 0) << "of " << rays << " rays through the shared edge";
  EXPECT_EQ(planar_misses, 0) << "of " << rays << " rays through the shared edge (planar test)";
}

// Grazing rays on quads: rays 1e-3 to 1 degree off the plane of a quad 1 to 1e3 units wide,
// aimed at interior points (5% inside the edges), hit it, and the hit point (from the
// barycentrics) lies on the target to 1e-5 of the quad's size; rays aimed 5% outside miss.
TEST(hard_Intersection, GrazingRaysOnQuads) {
  Uniform u(106);
  long misses = 0, false_hits = 0, planar_misses = 0, planar_false_hits = 0, rays = 0;
  double worst = 0;
  const vec2 z(0.0f);
  const vec3 up(0.0f, 1.0f, 0.0f);  // the quads' plane is y = 0 (both tests, same answers)
  for (double s : {1.0, 30.0, 1e3}) {
    const vec3 p0(float(-s / 2), 0.0f, float(-s / 2)), p1(float(-s / 2), 0.0f, float(s / 2)),
        p2(float(s / 2), 0.0f, float(-s / 2)), p3(float(s / 2), 0.0f, float(s / 2));
    for (int i = 0; i < 10000; ++i) {
      const double x = s * (-0.45 + 0.9 * u()), zc = s * (-0.45 + 0.9 * u());
      const double elevation = glm::radians(std::pow(10.0, -3.0 + 3.0 * u()));
      const double phi = 6.3 * u(), dist = s * (0.1 + 2.0 * u());
      const double side = i % 2 == 0 ? 1.0 : -1.0;
      const dvec3 dir(std::cos(elevation) * std::cos(phi), -side * std::sin(elevation), std::cos(elevation) * std::sin(phi));
      const dvec3 target(x, 0.0, zc);
      const F::Ray ray(vec3(target - dist * dir), vec3(dir));
      const F::QuadHit h = F::intersect_quad(ray, p0, p1, p2, p3, z, z, z, z, 0.0f, kInf);
      ++rays;
      planar_misses += F::intersect_planar_quad(ray, p0, p1, p2, p3, up, 0.0f, kInf) == F::NO_HIT;
      if (h.t == F::NO_HIT) {
        ++misses;
        continue;
      }
      worst = std::max(worst, glm::length(dvec3(h.position) - target) / s);
      const dvec3 outside(s * (0.55 + 0.4 * u()) * (u() < 0.5 ? -1 : 1), 0.0, s * (-0.45 + 0.9 * u()));
      const F::Ray miss(vec3(outside - dist * dir), vec3(dir));
      false_hits += F::intersect_quad(miss, p0, p1, p2, p3, z, z, z, z, 0.0f, kInf).t != F::NO_HIT;
      planar_false_hits += F::intersect_planar_quad(miss, p0, p1, p2, p3, up, 0.0f, kInf) != F::NO_HIT;
    }
  }
  // The ray's own rounding (its origin is off by eps |o|, up to eps 2.6 s) moves its plane
  // crossing by eps 2.6 s / sin(e): 0.02 s at 1e-3 degrees, inside the 5% margins. Lower
  // elevations are limited by the ray, not by the intersection.
  RecordProperty("worst_relative_position_error", std::to_string(worst));
  EXPECT_EQ(misses, 0) << "of " << rays;
  EXPECT_EQ(false_hits, 0) << "of " << rays;
  EXPECT_EQ(planar_misses, 0) << "of " << rays;
  EXPECT_EQ(planar_false_hits, 0) << "of " << rays;
}

// The same hit-point accuracy where it is well defined: elevations 0.1 to 10 degrees; the
// hit point is within (1e-5 + eps |o| / sin(e) / s) of the target, relative to the size.
TEST(hard_Intersection, GrazingQuadHitPointsAreAccurate) {
  Uniform u(107);
  const vec2 z(0.0f);
  for (double s : {1.0, 1e3}) {
    const vec3 p0(float(-s / 2), 0.0f, float(-s / 2)), p1(float(-s / 2), 0.0f, float(s / 2)),
        p2(float(s / 2), 0.0f, float(-s / 2)), p3(float(s / 2), 0.0f, float(s / 2));
    for (int i = 0; i < 10000; ++i) {
      const double x = s * (-0.45 + 0.9 * u()), zc = s * (-0.45 + 0.9 * u());
      const double elevation = glm::radians(std::pow(10.0, -1.0 + 2.0 * u()));
      const double phi = 6.3 * u(), dist = s * (0.1 + 2.0 * u());
      const dvec3 dir(std::cos(elevation) * std::cos(phi), -std::sin(elevation), std::cos(elevation) * std::sin(phi));
      const dvec3 target(x, 0.0, zc);
      const vec3 o = vec3(target - dist * dir);
      const F::Ray ray(o, vec3(dir));
      const F::QuadHit h = F::intersect_quad(ray, p0, p1, p2, p3, z, z, z, z, 0.0f, kInf);
      ASSERT_NE(h.t, F::NO_HIT);
      // Where the float ray (as rounded) really crosses y = 0, in double.
      const dvec3 od(o), dd(ray.direction);
      const dvec3 exact = od - (od.y / dd.y) * dd;
      const double tol = 16.0 * 0x1.0p-23 * (s + glm::length(od)) / std::sin(elevation) / s;
      ASSERT_LT(glm::length(dvec3(h.position) - exact) / s, tol) << "elevation " << elevation;
      ASSERT_NEAR(h.position.y, 0.0f, 0.0f);  // barycentric points of a y = 0 quad are exact in y
    }
  }
}

// Non-rectangular parallelograms (sheared, unequal sides, 1e-2 to 1e2 units, within 10 sizes
// of the origin, so that float corners resolve the barycentrics to ~1e-6), with affine texture coordinates (uv3 = uv1 + uv2 - uv0: both triangles
// give the same affine map) and with non-affine ones (uv3 free: each triangle interpolates its
// own corners, docs/DESIGN.md §6). Reference: the barycentrics of the hit in double against the
// triangle that contains it. Tolerance 1e-4 of the uv range, in float.
TEST(hard_Texture, ParallelogramTextureCoordinatesFollowTheTriangles) {
  Uniform u(108);
  long checked = 0;
  for (int q = 0; q < 200; ++q) {
    const double s = std::pow(10.0, -2.0 + 4.0 * u());
    const dvec3 a = 10.0 * s * u() * u.unit_vector();
    const dvec3 e1 = s * (0.3 + u()) * u.unit_vector();
    dvec3 e2 = s * (0.3 + u()) * u.unit_vector();
    if (glm::length(glm::cross(glm::normalize(e1), glm::normalize(e2))) < 0.3) continue;  // too thin
    const vec3 P[4] = {vec3(a), vec3(a + e1), vec3(a + e2), vec3(a + e1 + e2)};
    const dvec2 uv0(u(), u()), uv1(uv0 + dvec2(2 * u(), -u())), uv2(uv0 + dvec2(-u(), 3 * u()));
    const bool affine = q % 2 == 0;
    const dvec2 uv3 = affine ? uv1 + uv2 - uv0 : dvec2(5 * u(), 5 * u());
    const vec2 T[4] = {vec2(uv0), vec2(uv1), vec2(uv2), vec2(uv3)};
    const dvec3 n = glm::normalize(glm::cross(e1, e2));
    for (int i = 0; i < 200; ++i) {
      const double b1 = 0.01 + 0.98 * u(), b2 = 0.01 + 0.98 * u();
      const dvec3 target = dvec3(P[0]) + b1 * (dvec3(P[1]) - dvec3(P[0])) + b2 * (dvec3(P[2]) - dvec3(P[0]));
      dvec3 w = u.unit_vector();
      if (std::abs(glm::dot(w, n)) < 0.2) continue;
      const vec3 o = vec3(target + s * (1.0 + 5.0 * u()) * w);
      const F::QuadHit h = F::intersect_quad(F::Ray(o, vec3(glm::normalize(target - dvec3(o)))), P[0], P[1], P[2], P[3],
                                             T[0], T[1], T[2], T[3], 0.0f, kInf);
      ASSERT_NE(h.t, F::NO_HIT);
      // In parallelogram coordinates (b1, b2): triangle (p0, p1, p2) is b1 + b2 <= 1; the
      // other, (p1, p3, p2), has weights 1 - b2 (p1), b1 + b2 - 1 (p3), 1 - b1 (p2).
      dvec2 expected;
      if (b1 + b2 <= 1.0) {
        expected = (1.0 - b1 - b2) * uv0 + b1 * uv1 + b2 * uv2;
      } else {
        expected = (1.0 - b2) * uv1 + (b1 + b2 - 1.0) * uv3 + (1.0 - b1) * uv2;
      }
      if (!affine && std::abs(b1 + b2 - 1.0) < 1e-3) continue;  // the seam: either triangle
      const double range = 6.0;
      ASSERT_NEAR(h.uv.x, expected.x, 1e-4 * range) << "q " << q << " affine " << affine;
      ASSERT_NEAR(h.uv.y, expected.y, 1e-4 * range) << "q " << q << " affine " << affine;
      ++checked;
    }
  }
  EXPECT_GT(checked, 20000);
}

// Roughness from 0 to 1 (including both sides of the 0.03 delta threshold and 1e-6) for
// every material: sampling, evaluation and pdf never give NaN or infinity, over incoming
// directions down to cos = 1e-6 (float and double builds).
template <class L>
class hard_Roughness : public ::testing::Test {};
TYPED_TEST_SUITE(hard_Roughness, Precisions, PrecisionName);

TYPED_TEST(hard_Roughness, ZeroToOneNeverGivesNaN) {
  using L = TypeParam;
  using R = typename L::Real;
  Uniform u(109);
  const std::vector<double> roughness = {0.0, 1e-6, 1e-3, 0.01, 0.0299, 0.03, 0.0301, 0.031,
                                         0.05, 0.1, 0.25, 0.5, 0.75, 0.99, 1.0};
  long samples = 0;
  for (int type : {L::kMatte, L::kReflective, L::kGlossy, L::kTransparent, L::kRefractive}) {
    for (double rough : roughness) {
      typename L::SurfaceMaterial m(type, L::v3(0.9, 0.5, 0.1), R(rough), R(1.5));
      for (int i = 0; i < 4000; ++i) {
        const dvec3 nd = u.unit_vector();
        const double cos_o = i % 4 == 0 ? std::pow(10.0, -6.0 + 6.0 * u()) : u();
        const dvec3 wo = Frame(nd).to_world(cos_o, 6.3 * u());
        const typename L::vec3 n = L::v3(nd), wof = L::v3(wo);
        const typename L::BsdfSample s =
            L::sample_bsdf(m, n, wof, R(u()), L::v2(u(), u()));
        ++samples;
        if (!s.valid) continue;
        for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(double(s.weight[c]))) << type << " " << rough;
        ASSERT_TRUE(std::isfinite(double(s.pdf)));
        for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(double(s.wi[c])));
        const typename L::vec3 f = L::eval_bsdf(m, n, wof, s.wi);
        for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(double(f[c])));
        ASSERT_TRUE(std::isfinite(double(L::pdf_bsdf(m, n, wof, s.wi))));
        // A random direction too (eval and pdf are also called for those).
        const typename L::vec3 wr = L::v3(u.unit_vector());
        const typename L::vec3 fr = L::eval_bsdf(m, n, wof, wr);
        for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(double(fr[c])));
        ASSERT_TRUE(std::isfinite(double(L::pdf_bsdf(m, n, wof, wr))));
      }
    }
  }
  EXPECT_EQ(samples, 5L * 15 * 4000);
}

// Roughness 0.031 (just above the delta threshold, alpha = 9.6e-4) behaves like the mirror
// (roughness 0): for cos(theta_o) in [0.2, 1], (a) the mean sample weight (the directional
// albedo) agrees with the mirror's F(color, n.wo) within 1% plus 4 standard errors of the
// mean over N = 20000 samples, and (b) 95% of the sampled directions lie within 0.01 rad of
// the mirror direction (GGX: P(tan theta_h > x) = alpha^2 / (alpha^2 + x^2), so the 95th
// percentile of theta_h is alpha sqrt(19) = 4.2e-3, i.e. 8.4e-3 rad for wi). The 1% allows
// for the Smith masking of alpha ~ 1e-3 (below 1e-3 at these angles) and Fresnel at h
// instead of n. Float build.
TEST(hard_Roughness, NearZeroMatchesTheMirror) {
  Uniform u(110);
  const vec3 color(0.9f, 0.5f, 0.1f);
  const int n_samples = 20000;
  for (double cos_o : {0.2, 0.5, 0.9, 1.0}) {
    const vec3 n(0.0f, 0.0f, 1.0f);
    const vec3 wo = vec3(Frame(dvec3(n)).to_world(cos_o, 0.7));
    const F::SurfaceMaterial mirror(F::MATERIAL_REFLECTIVE, color, 0.0f, 1.5f);
    const F::SurfaceMaterial rough(F::MATERIAL_REFLECTIVE, color, 0.031f, 1.5f);
    const F::BsdfSample ms = F::sample_bsdf(mirror, n, wo, 0.5f, vec2(0.5f));
    ASSERT_TRUE(ms.valid && ms.delta);
    dvec3 sum(0.0), sum2(0.0);
    int close = 0;
    for (int i = 0; i < n_samples; ++i) {
      const F::BsdfSample s = F::sample_bsdf(rough, n, wo, float(u()), vec2(float(u()), float(u())));
      const dvec3 w = s.valid ? dvec3(s.weight) : dvec3(0.0);
      sum += w;
      sum2 += w * w;
      if (s.valid && std::acos(std::min(1.0, glm::dot(dvec3(s.wi), dvec3(ms.wi)))) < 0.01) ++close;
    }
    for (int c = 0; c < 3; ++c) {
      const double mean = sum[c] / n_samples;
      const double se = std::sqrt(std::max(0.0, sum2[c] / n_samples - mean * mean) / n_samples);
      EXPECT_NEAR(mean, ms.weight[c], 0.01 * ms.weight[c] + 4.0 * se) << "cos_o " << cos_o << " c " << c;
    }
    EXPECT_GE(close, int(0.95 * n_samples)) << "cos_o " << cos_o;
  }
}

}  // namespace
}  // namespace glint::shader_test
