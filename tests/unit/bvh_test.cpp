// The BVH of renderer/bvh.h and its traversal in shaders/lib/bvh.glsl (compiled as C++ through
// renderer/shader_lib.h): structure (every primitive in exactly one leaf, boxes nested and
// containing their shapes, depth within the shader's stack even for degenerate inputs) and the
// same closest hit as the plain loop of the same file, bit for bit, for many random rays.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "renderer/bvh.h"
#include "renderer/shader_lib.h"

namespace glint {
namespace {

struct Shapes {
  std::vector<GpuSphere> spheres;
  std::vector<GpuQuad> quads;
};

GpuSphere sphere(glm::vec3 c, float r) { return {glm::vec4(c, r), glm::ivec4(0, -1, 0, 0)}; }

GpuQuad quad(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3) {
  GpuQuad q{};
  q.p0 = glm::vec4(p0, 0);
  q.p1 = glm::vec4(p1, 0);
  q.p2 = glm::vec4(p2, 0);
  q.p3 = glm::vec4(p3, 0);
  q.uv01 = glm::vec4(0, 0, 0, 1);
  q.uv23 = glm::vec4(1, 0, 1, 1);
  q.normal = glm::vec4(glm::normalize(glm::cross(p1 - p0, p2 - p0)), 0);
  return q;
}

// Points the shader library at the shapes and the hierarchy (kept alive by the caller).
void view(const Shapes& s, const Bvh& bvh) {
  gpu::scene_view = {s.spheres.data(), static_cast<int>(s.spheres.size()), s.quads.data(),
                     static_cast<int>(s.quads.size()), bvh.nodes.data(), bvh.primitives.data()};
}

Bvh build(const Shapes& s, glm::vec3 camera = glm::vec3(0)) {
  return build_bvh(s.spheres, s.quads, ray_extent(s.spheres, s.quads, camera));
}

bool contains(const Aabb& outer, glm::vec3 lo, glm::vec3 hi) {
  return glm::all(glm::lessThanEqual(outer.lo, lo)) && glm::all(glm::greaterThanEqual(outer.hi, hi));
}

// Walks the tree from the root: every reference in exactly one leaf, leaves of 1..L
// primitives, interior boxes containing their children, leaf boxes their shapes' bounds,
// depth as recorded and within the stack bound.
void check_structure(const Shapes& s, const Bvh& bvh, float extent) {
  const size_t n = s.spheres.size() + s.quads.size();
  ASSERT_EQ(bvh.primitives.size(), n);
  ASSERT_FALSE(bvh.nodes.empty());
  if (n == 0) return;  // the traversal returns a miss without reading the root
  std::vector<int> seen(n, 0);
  struct Item {
    int node, depth;
  };
  std::vector<Item> todo = {{0, 0}};
  int max_depth = 0, visited = 0;
  while (!todo.empty()) {
    Item it = todo.back();
    todo.pop_back();
    ASSERT_GE(it.node, 0);
    ASSERT_LT(it.node, static_cast<int>(bvh.nodes.size()));
    ++visited;
    const GpuBvhNode& node = bvh.nodes[it.node];
    Aabb box{node.lo, node.hi};
    max_depth = std::max(max_depth, it.depth);
    if (node.count > 0) {
      ASSERT_LE(node.count, kBvhMaxLeafSize);
      for (int i = node.first; i < node.first + node.count; ++i) {
        int ref = bvh.primitives[static_cast<size_t>(i)];
        ASSERT_GE(ref, 0);
        ASSERT_LT(ref, static_cast<int>(n));
        ++seen[static_cast<size_t>(ref)];
        Aabb b = ref < static_cast<int>(s.spheres.size())
                     ? sphere_bounds(s.spheres[static_cast<size_t>(ref)], extent)
                     : quad_bounds(s.quads[static_cast<size_t>(ref) - s.spheres.size()], extent);
        ASSERT_TRUE(contains(box, b.lo, b.hi)) << "leaf " << it.node << " primitive " << ref;
      }
    } else {
      ASSERT_EQ(node.count, 0);
      for (int child : {it.node + 1, node.first}) {
        ASSERT_GT(child, it.node);  // depth-first order: no cycles
        const GpuBvhNode& c = bvh.nodes[static_cast<size_t>(child)];
        ASSERT_TRUE(contains(box, c.lo, c.hi)) << "node " << it.node << " child " << child;
        todo.push_back({child, it.depth + 1});
      }
    }
  }
  EXPECT_EQ(visited, static_cast<int>(bvh.nodes.size()));  // no unreachable nodes
  for (size_t i = 0; i < n; ++i) ASSERT_EQ(seen[i], 1) << "primitive " << i;
  EXPECT_EQ(max_depth, bvh.depth);
  EXPECT_LE(bvh.depth, kBvhMaxDepth);
  EXPECT_LE(kBvhMaxDepth, gpu::BVH_STACK_SIZE);
}

Shapes random_shapes(int spheres, int quads, uint32_t seed, float spread = 10) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1, 1);
  std::uniform_real_distribution<float> u01(0, 1);
  Shapes s;
  for (int i = 0; i < spheres; ++i) {
    glm::vec3 c(u(rng) * spread, u(rng) * spread, u(rng) * spread);
    s.spheres.push_back(sphere(c, 0.02f + 0.5f * u01(rng) * u01(rng)));
  }
  for (int i = 0; i < quads; ++i) {
    glm::vec3 c(u(rng) * spread, u(rng) * spread, u(rng) * spread);
    glm::vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    s.quads.push_back(quad(c, c + a, c + b, c + a + b + 0.1f * glm::vec3(u(rng), u(rng), u(rng))));
  }
  return s;
}

TEST(Bvh, StructureOfRandomScenes) {
  for (int n : {0, 1, 2, 3, 5, 17, 100, 1000}) {
    Shapes s = random_shapes(n, n / 3, 7u + static_cast<uint32_t>(n));
    float extent = ray_extent(s.spheres, s.quads, glm::vec3(0));
    Bvh bvh = build_bvh(s.spheres, s.quads, extent);
    SCOPED_TRACE(n);
    check_structure(s, bvh, extent);
    if (n + n / 3 > kBvhMaxLeafSize) {
      EXPECT_GT(bvh.leaf_count, 1);
    }
  }
}

TEST(Bvh, BoundsContainTheShapeWithPadding) {
  GpuSphere s = sphere({1e4f, -3, 0.5f}, 0.25f);
  Aabb b = sphere_bounds(s, 0);
  EXPECT_LT(b.lo.x, 1e4f - 0.25f);
  EXPECT_GT(b.hi.y, -3 + 0.25f);
  // Padding: 32 float epsilons of (the shape's coordinates + the ray origins' extent), here
  // 3.8e-6 * 10000.25 = 0.038, to the float spacing at 1e4 (0.001).
  EXPECT_NEAR(b.hi.x - (1e4f + 0.25f), 32.0 / 8388608.0 * 10000.25, 2e-3);
  Aabb far = sphere_bounds(sphere({0, 0, 0}, 1), 1000);
  EXPECT_LT(far.lo.x, -1 - 1000 * 3.0e-6f);
}

// Inputs that break naive builders: SAH finds no split (all centroids equal) or splits off one
// primitive at a time (sizes in geometric progression), and coordinates near the float range.
TEST(Bvh, DegenerateInputsStayWithinTheDepthBound) {
  struct Case {
    const char* name;
    Shapes shapes;
  };
  std::vector<Case> cases;
  {
    Shapes s;
    for (int i = 0; i < 100000; ++i) s.spheres.push_back(sphere({1, 2, 3}, 0.5f + 1e-6f * float(i % 7)));
    for (int i = 0; i < 1000; ++i) s.quads.push_back(quad({1, 2, 3}, {1, 2, 3.5f}, {1.5f, 2, 3}, {1.5f, 2, 3.5f}));
    cases.push_back({"all shapes at one point", std::move(s)});
  }
  {
    Shapes s;
    s.spheres.push_back(sphere({0, -1e5f, 0}, 1e5f));
    for (int i = 0; i < 2000; ++i) {
      float x = std::ldexp(1.0f, -(i % 120));  // nested scales: 1, 1/2, 1/4, ... 2^-119
      s.spheres.push_back(sphere({x, x, x}, x * 0.25f));
    }
    cases.push_back({"huge sphere with tiny ones at geometric spacing", std::move(s)});
  }
  {
    Shapes s;
    for (int i = 0; i < 3000; ++i) {
      float x = std::ldexp(1.0f, (i % 250) - 125);  // 2^-125 ... 2^124
      s.spheres.push_back(sphere({x, -x, 0.5f * x}, 0.1f * x));
    }
    s.spheres.push_back(sphere({1e38f, -1e38f, 1e38f}, 1e38f));
    s.quads.push_back(quad({-3e38f, 0, -3e38f}, {-3e38f, 0, 3e38f}, {3e38f, 0, -3e38f}, {3e38f, 0, 3e38f}));
    cases.push_back({"extreme coordinates", std::move(s)});
  }
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    float extent = ray_extent(c.shapes.spheres, c.shapes.quads, glm::vec3(0));
    Bvh bvh = build_bvh(c.shapes.spheres, c.shapes.quads, extent);
    check_structure(c.shapes, bvh, extent);
    std::printf("%s: %zu primitives, depth %d, %zu nodes\n", c.name, bvh.primitives.size(), bvh.depth, bvh.nodes.size());
  }
}

TEST(Bvh, MillionIdenticalSpheres) {
  Shapes s;
  s.spheres.assign(1000000, sphere({0.5f, 0.5f, 0.5f}, 1));
  auto start = std::chrono::steady_clock::now();
  Bvh bvh = build(s);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("10^6 identical spheres: depth %d, build %.3f s\n", bvh.depth, seconds);
  // Median splits all the way: ceil(log2(10^6 / 4)) = 18 levels.
  EXPECT_EQ(bvh.depth, 18);
  check_structure(s, bvh, ray_extent(s.spheres, s.quads, glm::vec3(0)));
  // The loop takes the first sphere on a tie, and so must the BVH.
  view(s, bvh);
  gpu::Ray ray(glm::vec3(0.5f, 0.5f, 5), glm::vec3(0, 0, -1));
  gpu::PrimitiveHit h = gpu::closest_hit_bvh(ray, 1e30f, 1 << 30);
  EXPECT_EQ(h.ref, 0);
  EXPECT_EQ(h.t, 3.5f);  // the sphere's near side, z = 1.5
}

// Rays that test the padding and the tie-breaking: from near and far origins, axis-aligned
// (zero direction components), aimed at sphere silhouettes and quad edges and corners, and
// through coincident shapes.
std::vector<gpu::Ray> random_rays(const Shapes& s, int n, uint32_t seed, float spread) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<gpu::Ray> rays;
  auto unit = [&] {
    for (;;) {
      glm::vec3 d(u(rng), u(rng), u(rng));
      float l = glm::length(d);
      if (l > 0.1f && l <= 1) return d / l;
    }
  };
  for (int i = 0; i < n; ++i) {
    float reach = (i % 4 == 0) ? 1000.0f * spread : 2.0f * spread;
    glm::vec3 o = glm::vec3(u(rng), u(rng), u(rng)) * reach;
    glm::vec3 d;
    switch (i % 5) {
      case 0: d = unit(); break;
      case 1: {  // axis-aligned
        d = glm::vec3(0);
        d[i / 5 % 3] = u(rng) < 0 ? -1.0f : 1.0f;
        if (!s.spheres.empty()) {
          glm::vec3 c(s.spheres[static_cast<size_t>(i) % s.spheres.size()].center_radius);
          o = c - d * (spread * 3);
          o[(i / 5 + 1) % 3] += u(rng) * 0.3f;
        }
        break;
      }
      case 2:
        if (!s.spheres.empty()) {  // at a silhouette: a point at distance r from the centre
          glm::vec4 cr = s.spheres[static_cast<size_t>(i * 7919) % s.spheres.size()].center_radius;
          glm::vec3 to = glm::vec3(cr) - o;
          glm::vec3 side = glm::normalize(glm::cross(to, unit()));
          d = glm::normalize(glm::vec3(cr) + side * cr.w * (1 + 1e-6f * u(rng)) - o);
        } else {
          d = unit();
        }
        break;
      default:
        if (!s.quads.empty()) {  // at a quad corner or edge
          const GpuQuad& q = s.quads[static_cast<size_t>(i * 104729) % s.quads.size()];
          float w = (u(rng) + 1) / 2;
          glm::vec3 target = i % 2 ? glm::vec3(q.p0) : glm::mix(glm::vec3(q.p1), glm::vec3(q.p2), w);
          d = glm::normalize(target - o);
        } else {
          d = unit();
        }
    }
    rays.push_back(gpu::Ray(o, d));
  }
  return rays;
}

// Whether the loop's hit is where the shape is: the point o + t d (in double) inside the shape's
// padded box. The quad test (intersect.glsl) decides from edge volumes d.(a x b) with a, b the
// corners relative to the origin: products of size |a|^2 whose difference, for a ray passing the
// quad at distance h, is about h |edge| |a|. Rounding blurs the decision by eps |a|^2 / |edge|:
// 27 units for a unit quad seen from 1.5e4 (the first such "hit" this test found passed 8 units
// from its quad). That is a limit of the loop's quad test, not of the BVH: such a hit lies outside
// any padding, and the BVH, which tests only primitives whose boxes the ray enters before the
// best hit, may report another primitive. Every other ray must get the same hit, bit for bit.
bool loop_hit_is_sound(const Shapes& s, const gpu::Ray& ray, const gpu::PrimitiveHit& h, float extent) {
  if (h.ref < 0) return true;
  Aabb b = h.ref < static_cast<int>(s.spheres.size())
               ? sphere_bounds(s.spheres[static_cast<size_t>(h.ref)], extent)
               : quad_bounds(s.quads[static_cast<size_t>(h.ref) - s.spheres.size()], extent);
  glm::dvec3 p = glm::dvec3(ray.origin) + double(h.t) * glm::dvec3(ray.direction);
  return glm::all(glm::lessThanEqual(glm::dvec3(b.lo), p)) && glm::all(glm::lessThanEqual(p, glm::dvec3(b.hi)));
}

// Ray origins reach 1000 * spread: the box padding is told so through the camera position.
void expect_same_hits(const Shapes& s, int rays, uint32_t seed, float spread, double max_unsound) {
  const glm::vec3 camera(1000 * spread);
  const float extent = ray_extent(s.spheres, s.quads, camera);
  Bvh bvh = build(s, camera);
  view(s, bvh);
  int hits = 0, differ = 0, unsound = 0;
  long steps = 0;
  for (const gpu::Ray& ray : random_rays(s, rays, seed, spread)) {
    gpu::PrimitiveHit loop = gpu::closest_hit_loop(ray, 1e30f);
    gpu::PrimitiveHit tree = gpu::closest_hit_bvh(ray, 1e30f, 1 << 30);
    ASSERT_TRUE(tree.complete);
    steps += tree.steps;
    if (loop.ref >= 0) ++hits;
    if (!loop_hit_is_sound(s, ray, loop, extent)) {
      ++unsound;
      continue;
    }
    if (loop.ref != tree.ref || loop.t != tree.t) {
      if (++differ <= 5)
        ADD_FAILURE() << "ray (" << ray.origin.x << "," << ray.origin.y << "," << ray.origin.z << ") -> ("
                      << ray.direction.x << "," << ray.direction.y << "," << ray.direction.z << "): loop "
                      << loop.ref << " at " << loop.t << ", bvh " << tree.ref << " at " << tree.t;
    }
  }
  std::printf("%zu spheres, %zu quads: %d of %d rays hit, %d unsound loop hits, %d differ, %.1f nodes per ray\n",
              s.spheres.size(), s.quads.size(), hits, rays, unsound, differ, double(steps) / rays);
  EXPECT_EQ(differ, 0);
  EXPECT_GT(hits, rays / 10);       // the rays do find shapes
  EXPECT_LE(unsound, max_unsound * rays);  // the exemption does not swallow the test
}

TEST(Bvh, SameHitAsTheLoop) {
  // Spheres are sound from any origin (their test blurs by eps |o - c| only, which the padding
  // covers); quads seen from a quarter of the origins, 1000 scene sizes away, are not always.
  expect_same_hits(random_shapes(2000, 500, 1), 20000, 2, 10, 0.15);
  expect_same_hits(random_shapes(300, 0, 3), 5000, 4, 10, 0.0);
  expect_same_hits(random_shapes(0, 300, 5), 5000, 6, 10, 0.15);
  // Coincident duplicates (ties) and a scene 1000 units from the camera.
  Shapes dup = random_shapes(200, 60, 7, 3);
  Shapes copy = dup;
  dup.spheres.insert(dup.spheres.end(), copy.spheres.begin(), copy.spheres.end());
  dup.quads.insert(dup.quads.end(), copy.quads.begin(), copy.quads.end());
  expect_same_hits(dup, 5000, 8, 3, 0.15);
  Shapes far = random_shapes(500, 100, 9, 1);
  for (GpuSphere& sp : far.spheres) sp.center_radius += glm::vec4(1000, 0, 0, 0);
  for (GpuQuad& q : far.quads)
    for (glm::vec4* p : {&q.p0, &q.p1, &q.p2, &q.p3}) *p += glm::vec4(1000, 0, 0, 0);
  expect_same_hits(far, 5000, 10, 1, 0.15);
}

// Rays parallel to an axis that touch a sphere at its extreme point in that slab: the loop's
// test reports the tangent hit (discriminant exactly 0 with these exact values), and only the
// padding keeps that point strictly inside the box (on the box's face, a ray with a zero
// direction component gets an empty slab interval, bvh.glsl's safe_inverse).
TEST(Bvh, TangentRaysAtExtremePointsAreFound) {
  Shapes s;
  for (int i = 0; i < 64; ++i)
    s.spheres.push_back(sphere({0.5f * float(i % 8), 0.25f * float(i / 8), -2}, 0.125f + 0.0625f * float(i % 3)));
  Bvh bvh = build(s);
  view(s, bvh);
  int tangent_hits = 0;
  for (size_t i = 0; i < s.spheres.size(); ++i) {
    glm::vec4 cr = s.spheres[i].center_radius;
    for (int axis = 0; axis < 3; ++axis)
      for (float side : {-1.0f, 1.0f}) {
        glm::vec3 p(cr);
        p[axis] += side * cr.w;  // the extreme point
        glm::vec3 d(0);
        d[(axis + 1) % 3] = 1;
        gpu::Ray ray(p - 10.0f * d, d);
        gpu::PrimitiveHit loop = gpu::closest_hit_loop(ray, 1e30f);
        gpu::PrimitiveHit tree = gpu::closest_hit_bvh(ray, 1e30f, 1 << 30);
        if (loop.ref == static_cast<int>(i) && loop.t == 10.0f) ++tangent_hits;
        EXPECT_EQ(tree.ref, loop.ref) << "sphere " << i << " axis " << axis << " side " << side;
        EXPECT_EQ(tree.t, loop.t);
      }
  }
  std::printf("%d tangent hits\n", tangent_hits);
  EXPECT_GT(tangent_hits, 0);
}

// A capped traversal says so, and never reports a hit it did not verify.
TEST(Bvh, StepCapIsReported) {
  Shapes s = random_shapes(5000, 0, 11);
  Bvh bvh = build(s);
  view(s, bvh);
  int incomplete = 0;
  for (const gpu::Ray& ray : random_rays(s, 2000, 12, 10)) {
    gpu::PrimitiveHit h = gpu::closest_hit_bvh(ray, 1e30f, 3);
    EXPECT_LE(h.steps, 3);
    if (!h.complete) ++incomplete;
    if (h.ref >= 0) {
      EXPECT_EQ(gpu::scene_primitive_hit(h.ref, ray, gpu::next_float_up(h.t)), h.t);
    }
  }
  EXPECT_GT(incomplete, 0);
}

TEST(Bvh, BuildTime) {
  for (int n : {10000, 100000}) {
    Shapes s = random_shapes(n, n / 100, 13, 100);
    auto start = std::chrono::steady_clock::now();
    Bvh bvh = build(s);
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%d spheres + %d quads: build %.1f ms, %zu nodes, depth %d\n", n, n / 100, seconds * 1e3,
                bvh.nodes.size(), bvh.depth);
    EXPECT_EQ(bvh.primitives.size(), static_cast<size_t>(n + n / 100));
  }
}

}  // namespace
}  // namespace glint
