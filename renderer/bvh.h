// A bounding volume hierarchy over the packed spheres and quads (renderer/gpu_scene.h), built on
// the CPU and traversed by shaders/lib/bvh.glsl. Built with binned SAH (Wald, "On fast
// Construction of SAH-based Bounding Volume Hierarchies", IEEE RT 2007), flattened depth-first
// into an array of 32-byte std430 nodes; leaves hold up to kBvhMaxLeafSize primitive references
// in a separate index list.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/gpu_scene.h"
#include "renderer/render_options.h"

namespace glint {

// The layout of BvhNode in shaders/lib/bvh.glsl.
struct GpuBvhNode {
  glm::vec3 lo{0};
  int32_t first = 0;  // leaf: first entry of the index list; interior: the second child
  glm::vec3 hi{0};
  int32_t count = 0;  // leaf: number of primitives (>= 1); interior: 0 (first child: next node)
};
static_assert(sizeof(GpuBvhNode) == 32, "std430 layout of BvhNode");

// The shader's traversal stack holds at most one entry per level (BVH_STACK_SIZE in bvh.glsl):
// no leaf may be deeper than this (the root has depth 0).
constexpr int kBvhMaxDepth = 32;
constexpr int kBvhMaxLeafSize = 4;

struct Aabb {
  glm::vec3 lo{0};
  glm::vec3 hi{0};
};

struct Bvh {
  std::vector<GpuBvhNode> nodes;  // nodes[0] is the root; never empty
  std::vector<int32_t> primitives;  // references: sphere i is i, quad j is spheres.size() + j
  int depth = 0;                    // of the deepest leaf
  int leaf_count = 0;
};

// Conservative float boxes of a packed sphere or quad, for rays whose origins have coordinates
// of magnitude at most `ray_extent` (see bvh.cpp for why that matters and the padding).
Aabb sphere_bounds(const GpuSphere& s, float ray_extent);
Aabb quad_bounds(const GpuQuad& q, float ray_extent);

// The largest coordinate magnitude a ray origin can have in this packed scene: the shapes'
// own extent and the camera's position relative to the render origin.
float ray_extent(const std::vector<GpuSphere>& spheres, const std::vector<GpuQuad>& quads,
                 const glm::vec3& camera);

// Builds the hierarchy. Any number of primitives (0 gives a placeholder root); leaves
// are never deeper than kBvhMaxDepth whatever the input (a median split takes over from SAH
// where a deeper tree could follow).
Bvh build_bvh(const std::vector<GpuSphere>& spheres, const std::vector<GpuQuad>& quads,
              float ray_extent);

// Recomputes every box bottom-up for shapes that moved, keeping the tree: a few hundred times
// cheaper than a build, for edits that keep the number of shapes (an editor drag). False, and
// nothing changed, when the counts differ from the tree's.
bool refit_bvh(Bvh& bvh, const std::vector<GpuSphere>& spheres, const std::vector<GpuQuad>& quads,
               float ray_extent);

// The surface area heuristic cost of the tree (expected node visits plus primitive tests per
// ray, for rays uniform over the root box's surface): refitting after large moves makes it grow.
double sah_cost(const Bvh& bvh);

// Shapes from which the BVH beats the plain loop. Measured on Mesa llvmpipe (this 2-core
// machine, shared, so noisy): `python3 bench/tools/scale.py --sizes 4,8,16,32,64,128 --repeats 5
// --spp 8` (64x64 pixels, 4 bounces, a grid of spheres on a floor quad), median samples per
// pixel per second loop / BVH: 4 spheres 123 / 82, 8: 60 / 58, 16: 70 / 42, 32: 39 / 34,
// 64: 19 / 27, 128: 11 / 23; again with bench/tools/scale.py's fixed framing (shapes shrinking with
// N, one floor quad): 4: 130 / 89, 8: 76 / 49, 16: 58 / 48, 32: 45 / 43, 64: 29 / 39,
// 128: 16 / 34. The crossover lies between 33 and 65 shapes; 48 is between.
constexpr long kBvhCrossoverShapes = 48;

// The renderer's choice: the forced one, or with Accel::automatic the BVH from
// kBvhCrossoverShapes shapes and wherever one sample of the loop would exceed llvmpipe's loop
// limit (renderer/loop_budget.h). Never for an empty scene.
bool use_bvh(Accel accel, long shapes, int max_bounces);

}  // namespace glint
