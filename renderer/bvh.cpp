#include "renderer/bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "renderer/loop_budget.h"

namespace glint {
namespace {

// Boxes are computed in double and rounded outwards to float at the end, so that extreme but
// finite coordinates (1e38) neither overflow an area nor lose the shape to rounding.
struct DBox {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};
  void grow(const DBox& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  void grow(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  bool empty() const { return !(lo.x <= hi.x); }
  double half_area() const {
    if (empty()) return 0;
    glm::dvec3 e = hi - lo;
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }
};

// Why the padding, and how much: a box must contain every point where the loop's float
// intersection routines (shaders/lib/intersect.glsl) can report a hit, not only the exact
// shape, or the BVH would skip hits the loop finds (and the images would differ). The sphere
// test decides hit or miss from closest = f - (b/a) d with f = o - c: each term has magnitude
// |o - c| <= |o| + |c|, so the decision is blurred by a few float epsilons of |o| + |c| (a ray
// passing 1e-4 outside a unit sphere 1000 units from the camera may still hit it). The slab
// test of the traversal rounds (lo - o) at the same scale. (The quad test's edge volumes blur by
// eps |o - p|^2 / |edge| instead, which no padding linear in the coordinates covers: from far
// enough away its hits are rounding noise, see tests/unit/bvh_test.cpp; near the camera, where
// it matters, the padding below covers it.) So each box grows by kPad times (the shape's largest coordinate + the largest ray
// origin coordinate): 32 float epsilons, several times the few epsilons the rounding amounts
// to. In ordinary scenes that is micrometres per metre; a scene with a 1e5 floor sphere pads
// every box by about 0.4 (rays may start anywhere on that sphere), which costs speed, not
// correctness. unit.Bvh.SameHitAsTheLoop checks grazing rays from far origins.
constexpr double kPad = 32.0 / 8388608.0;

float round_down(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
float round_up(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

double max_abs(const glm::dvec3& p) { return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}); }

DBox padded(DBox b, double own_extent, double ray_extent) {
  double pad = kPad * (own_extent + ray_extent) + 1e-30;
  b.lo -= pad;
  b.hi += pad;
  return b;
}

DBox sphere_box(const GpuSphere& s, double ray_extent) {
  glm::dvec3 c(s.center_radius);
  double r = std::abs(static_cast<double>(s.center_radius.w));
  DBox b;
  b.lo = c - r;
  b.hi = c + r;
  return padded(b, max_abs(c) + r, ray_extent);
}

DBox quad_box(const GpuQuad& q, double ray_extent) {
  DBox b;
  for (const glm::vec4& p : {q.p0, q.p1, q.p2, q.p3}) b.grow(glm::dvec3(p));
  return padded(b, std::max(max_abs(b.lo), max_abs(b.hi)), ray_extent);
}

Aabb to_float(const DBox& b) {
  return {glm::vec3(round_down(b.lo.x), round_down(b.lo.y), round_down(b.lo.z)),
          glm::vec3(round_up(b.hi.x), round_up(b.hi.y), round_up(b.hi.z))};
}

// Levels of median splits that take n primitives down to leaves of kBvhMaxLeafSize:
// ceil(log2(ceil(n / L))). A median split lowers it by exactly one.
int levels_needed(long n) {
  long leaves = (n + kBvhMaxLeafSize - 1) / kBvhMaxLeafSize;
  int levels = 0;
  while ((1L << levels) < leaves) ++levels;
  return levels;
}

constexpr int kBins = 16;

struct Split {
  int axis = -1;
  int bin = 0;       // primitives in bins <= bin go left
  double cost = 0;   // SAH cost relative to the parent's area (traversal step = 1)
  long left = 0, right = 0;
};

class Builder {
 public:
  Builder(std::vector<DBox> boxes) : boxes_(std::move(boxes)) {
    centroids_.reserve(boxes_.size());
    for (const DBox& b : boxes_) centroids_.push_back(0.5 * b.lo + 0.5 * b.hi);
    refs_.resize(boxes_.size());
    for (size_t i = 0; i < refs_.size(); ++i) refs_[i] = static_cast<int32_t>(i);
    bvh_.nodes.reserve(2 * boxes_.size() + 1);
  }

  Bvh run() {
    if (boxes_.empty()) {
      // A placeholder root (a buffer is never empty); the traversal returns a miss without
      // reading it when there are no primitives.
      bvh_.nodes.emplace_back();
      return std::move(bvh_);
    }
    build(0, static_cast<long>(refs_.size()), 0);
    bvh_.primitives = std::move(refs_);
    return std::move(bvh_);
  }

 private:
  int bin_of(const glm::dvec3& c, int axis, const DBox& cb) const {
    double extent = cb.hi[axis] - cb.lo[axis];
    int b = static_cast<int>((c[axis] - cb.lo[axis]) / extent * kBins);
    return std::clamp(b, 0, kBins - 1);
  }

  // Wald 2007: primitives are binned by centroid along each axis, and the split planes between
  // bins are scored with the surface area heuristic from the bins' counts and boxes.
  Split best_split(long begin, long end, const DBox& cb, double parent_area) const {
    Split best;
    for (int axis = 0; axis < 3; ++axis) {
      if (!(cb.hi[axis] - cb.lo[axis] > 0)) continue;
      long count[kBins] = {};
      DBox box[kBins];
      for (long i = begin; i < end; ++i) {
        int b = bin_of(centroids_[refs_[i]], axis, cb);
        ++count[b];
        box[b].grow(boxes_[refs_[i]]);
      }
      double right_area[kBins];
      long right_count[kBins];
      DBox acc;
      long n = 0;
      for (int b = kBins - 1; b > 0; --b) {
        acc.grow(box[b]);
        n += count[b];
        right_area[b] = acc.half_area();
        right_count[b] = n;
      }
      acc = DBox();
      n = 0;
      for (int b = 0; b < kBins - 1; ++b) {
        acc.grow(box[b]);
        n += count[b];
        if (n == 0 || right_count[b + 1] == 0) continue;
        double cost = 1.0 + (acc.half_area() * static_cast<double>(n) +
                             right_area[b + 1] * static_cast<double>(right_count[b + 1])) /
                                parent_area;
        if (best.axis < 0 || cost < best.cost) best = {axis, b, cost, n, right_count[b + 1]};
      }
    }
    return best;
  }

  long partition_by(const Split& s, long begin, long end, const DBox& cb) {
    auto mid = std::partition(refs_.begin() + begin, refs_.begin() + end, [&](int32_t r) {
      return bin_of(centroids_[r], s.axis, cb) <= s.bin;
    });
    return mid - refs_.begin();
  }

  // Half of the primitives (rounded up) by centroid along the widest axis, ties by reference.
  long partition_median(long begin, long end, const DBox& cb) {
    glm::dvec3 e = cb.empty() ? glm::dvec3(0) : cb.hi - cb.lo;
    int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
    long mid = begin + (end - begin + 1) / 2;
    std::nth_element(refs_.begin() + begin, refs_.begin() + mid, refs_.begin() + end,
                     [&](int32_t a, int32_t b) {
                       double ca = centroids_[a][axis], cb2 = centroids_[b][axis];
                       return ca < cb2 || (ca == cb2 && a < b);
                     });
    return mid;
  }

  int build(long begin, long end, int depth) {
    const int index = static_cast<int>(bvh_.nodes.size());
    bvh_.nodes.emplace_back();
    DBox box, cb;
    for (long i = begin; i < end; ++i) {
      box.grow(boxes_[refs_[i]]);
      cb.grow(centroids_[refs_[i]]);
    }
    Aabb fb = to_float(box);
    bvh_.nodes[index].lo = fb.lo;
    bvh_.nodes[index].hi = fb.hi;
    const long n = end - begin;
    Split s;
    if (n > 1) s = best_split(begin, end, cb, std::max(box.half_area(), 1e-300));
    // SAH only where the deeper child can still be finished by median splits within the depth
    // bound; otherwise (long chains of SAH splits, e.g. a huge sphere among tiny ones) median.
    const bool sah_ok = s.axis >= 0 && depth + 1 + levels_needed(std::max(s.left, s.right)) <= kBvhMaxDepth;
    if (n <= kBvhMaxLeafSize && (!sah_ok || static_cast<double>(n) <= s.cost)) {
      bvh_.nodes[index].first = static_cast<int32_t>(begin);
      bvh_.nodes[index].count = static_cast<int32_t>(n);
      bvh_.depth = std::max(bvh_.depth, depth);
      ++bvh_.leaf_count;
      return index;
    }
    const long mid = sah_ok ? partition_by(s, begin, end, cb) : partition_median(begin, end, cb);
    build(begin, mid, depth + 1);  // node index + 1
    const int second = build(mid, end, depth + 1);
    bvh_.nodes[index].first = second;
    bvh_.nodes[index].count = 0;
    return index;
  }

  std::vector<DBox> boxes_;
  std::vector<glm::dvec3> centroids_;
  std::vector<int32_t> refs_;
  Bvh bvh_;
};

}  // namespace

Aabb sphere_bounds(const GpuSphere& s, float ray_extent) { return to_float(sphere_box(s, ray_extent)); }
Aabb quad_bounds(const GpuQuad& q, float ray_extent) { return to_float(quad_box(q, ray_extent)); }

float ray_extent(const std::vector<GpuSphere>& spheres, const std::vector<GpuQuad>& quads,
                 const glm::vec3& camera) {
  double m = max_abs(glm::dvec3(camera));
  for (const GpuSphere& s : spheres)
    m = std::max(m, max_abs(glm::dvec3(s.center_radius)) + std::abs(double(s.center_radius.w)));
  for (const GpuQuad& q : quads)
    for (const glm::vec4& p : {q.p0, q.p1, q.p2, q.p3}) m = std::max(m, max_abs(glm::dvec3(p)));
  return round_up(m);
}

bool refit_bvh(Bvh& bvh, const std::vector<GpuSphere>& spheres, const std::vector<GpuQuad>& quads,
               float ray_extent) {
  const size_t n = spheres.size() + quads.size();
  if (n == 0 || bvh.primitives.size() != n) return false;
  auto box_of = [&](int32_t ref) {
    size_t r = static_cast<size_t>(ref);
    return r < spheres.size() ? sphere_box(spheres[r], ray_extent) : quad_box(quads[r - spheres.size()], ray_extent);
  };
  // Children follow their parent in the array: a backward pass sees children first. The float
  // boxes of children are unions of rounded-outward boxes, so their union stays conservative.
  for (size_t i = bvh.nodes.size(); i-- > 0;) {
    GpuBvhNode& node = bvh.nodes[i];
    if (node.count > 0) {
      DBox b;
      for (int k = node.first; k < node.first + node.count; ++k) b.grow(box_of(bvh.primitives[static_cast<size_t>(k)]));
      Aabb f = to_float(b);
      node.lo = f.lo;
      node.hi = f.hi;
    } else {
      const GpuBvhNode& a = bvh.nodes[i + 1];
      const GpuBvhNode& c = bvh.nodes[static_cast<size_t>(node.first)];
      node.lo = glm::min(a.lo, c.lo);
      node.hi = glm::max(a.hi, c.hi);
    }
  }
  return true;
}

double sah_cost(const Bvh& bvh) {
  auto half_area = [](const GpuBvhNode& n) {
    glm::dvec3 e = glm::max(glm::dvec3(n.hi) - glm::dvec3(n.lo), glm::dvec3(0));
    return e.x * e.y + e.y * e.z + e.z * e.x;
  };
  const double root = half_area(bvh.nodes[0]);
  if (!(root > 0) || bvh.primitives.empty()) return 0;
  double cost = 0;
  for (const GpuBvhNode& n : bvh.nodes) cost += half_area(n) / root * (n.count > 0 ? 1.0 + n.count : 1.0);
  return cost;
}

bool use_bvh(Accel accel, long shapes, int max_bounces) {
  if (shapes <= 0 || accel == Accel::loop) return false;
  if (accel == Accel::bvh) return true;
  return shapes >= kBvhCrossoverShapes ||
         loop_iterations_per_sample(shapes, max_bounces) > kLlvmpipeLoopLimit;
}

Bvh build_bvh(const std::vector<GpuSphere>& spheres, const std::vector<GpuQuad>& quads,
              float ray_extent) {
  std::vector<DBox> boxes;
  boxes.reserve(spheres.size() + quads.size());
  for (const GpuSphere& s : spheres) boxes.push_back(sphere_box(s, ray_extent));
  for (const GpuQuad& q : quads) boxes.push_back(quad_box(q, ray_extent));
  return Builder(std::move(boxes)).run();
}

}  // namespace glint
