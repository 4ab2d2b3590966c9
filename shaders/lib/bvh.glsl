// The closest primitive along a ray: the plain loop over every sphere and quad, and the
// traversal of the bounding volume hierarchy of renderer/bvh.h. Both report the same primitive
// (ties broken the same way), so the renderer may use either for any scene.
//
// A lib file cannot declare buffers: the includer supplies the scene through the functions
// declared below (shaders/trace_common.glsl from its table textures, renderer/shader_lib.h from
// arrays on the CPU), defined after this file is included.
#ifndef GLINT_BVH_GLSL
#define GLINT_BVH_GLSL

// One node, 32 bytes in std430 (a vec3 and an int share 16 bytes), as glint::GpuBvhNode.
// count > 0: a leaf holding primitive references [first, first + count) of the index list.
// count == 0: an interior node; its first child is the next node (depth-first order), its
// second child is node `first`.
struct BvhNode {
  vec3 lo;
  int first;
  vec3 hi;
  int count;
};

int scene_sphere_count();
int scene_quad_count();
// The nearest t in (0, tmax) where the ray meets sphere i (quad i), or NO_HIT.
float scene_sphere_hit(int i, Ray ray, float tmax);
float scene_quad_hit(int i, Ray ray, float tmax);
BvhNode bvh_node(int i);
int bvh_primitive(int i);  // a primitive reference: sphere i is i, quad j is sphere count + j

// The traversal stack: a node's far child is pushed while its near child is visited, so the
// stack holds at most one entry per level above the current node. renderer/bvh.cpp builds trees
// of depth (edges from the root to a leaf) at most kBvhMaxDepth == BVH_STACK_SIZE.
const int BVH_STACK_SIZE = 32;

struct PrimitiveHit {
  float t;
  int ref;        // primitive reference, -1 for none
  int steps;      // BVH nodes visited (0 for the loop)
  bool complete;  // false: the BVH traversal stopped at its step cap (the hit may be wrong)
};

// A primitive's reported t is its nearest hit in (0, tmax), whatever tmax is (the intersection
// routines compute t without looking at tmax), so the closest hit is the least (t, ref) in
// lexicographic order: the loop below finds it by testing spheres, then quads, in order with a
// strict `t < best`. The BVH visits primitives in another order and gets the same answer by
// also accepting t == best for a lower reference: for those it tests against the next float up.
float next_float_up(float t) { return uintBitsToFloat(floatBitsToUint(t) + 1u); }

// A trace program for a scene without quads (GLINT_NO_QUADS) or without spheres
// (GLINT_NO_SPHERES) leaves out that shape's code: on llvmpipe an untaken branch still runs
// (renderer/shader_features.h).
float scene_primitive_hit(int ref, Ray ray, float tmax) {
  int spheres = scene_sphere_count();
#if defined(GLINT_NO_QUADS)
  return scene_sphere_hit(ref, ray, tmax);
#elif defined(GLINT_NO_SPHERES)
  return scene_quad_hit(ref - spheres, ray, tmax);
#else
  if (ref < spheres) return scene_sphere_hit(ref, ray, tmax);
  return scene_quad_hit(ref - spheres, ray, tmax);
#endif
}

PrimitiveHit closest_hit_loop(Ray ray, float tmax) {
  PrimitiveHit best = PrimitiveHit(tmax, -1, 0, true);
  int spheres = scene_sphere_count();
#if !defined(GLINT_NO_SPHERES)
  for (int i = 0; i < spheres; ++i) {
    float t = scene_sphere_hit(i, ray, best.t);
    if (t != NO_HIT) {
      best.t = t;
      best.ref = i;
    }
  }
#endif
#if !defined(GLINT_NO_QUADS)
  int quads = scene_quad_count();
  for (int i = 0; i < quads; ++i) {
    float t = scene_quad_hit(i, ray, best.t);
    if (t != NO_HIT) {
      best.t = t;
      best.ref = spheres + i;
    }
  }
#endif
  return best;
}

// 1 / d with zero components replaced by 1e30: (lo - o) * 1e30 is 0 or large, never the
// 0 * inf = NaN of a ray lying in a slab's plane (such a ray meets no primitive there: boxes are
// padded beyond their shapes, renderer/bvh.cpp).
vec3 safe_inverse(vec3 d) {
  return vec3(1.0f / (abs(d.x) > 1e-30f ? d.x : 1e-30f), 1.0f / (abs(d.y) > 1e-30f ? d.y : 1e-30f),
              1.0f / (abs(d.z) > 1e-30f ? d.z : 1e-30f));
}

// Entry and exit distances of the ray through a box (slab test, Kay and Kajiya 1986). The exit
// is scaled by 1 + 2 gamma(3) (Ize, "Robust BVH Ray Traversal", JCGT 2013) so that rounding of
// the slab distances never makes a ray that touches the box miss it.
const float BVH_EXIT_SCALE = 1.0000008f;
vec2 box_interval(vec3 lo, vec3 hi, Ray ray, vec3 inv_dir) {
  vec3 t0 = (lo - ray.origin) * inv_dir;
  vec3 t1 = (hi - ray.origin) * inv_dir;
  vec3 near_t = min(t0, t1);
  vec3 far_t = max(t0, t1);
  float enter = max(max(near_t.x, near_t.y), max(near_t.z, 0.0f));
  float exit = min(min(far_t.x, far_t.y), far_t.z) * BVH_EXIT_SCALE;
  return vec2(enter, exit);
}

// The box can hold a hit at most as far as `best` (inclusive: ties matter, see above).
bool box_worth_visiting(vec2 interval, float best) {
  return interval.x <= interval.y && interval.x <= best;
}

// Closest hit by BVH traversal, nearer child first, skipping boxes that start beyond the best
// hit so far. At most max_steps nodes are visited: the trace shader must bound its loops (Mesa
// 22's llvmpipe ends every loop of an invocation after 65535 iterations in all, renderer/
// loop_budget.h), and a traversal stopped early says so (complete == false) instead of
// returning a wrong hit unnoticed.
PrimitiveHit closest_hit_bvh(Ray ray, float tmax, int max_steps) {
  PrimitiveHit best = PrimitiveHit(tmax, -1, 0, true);
  if (scene_sphere_count() + scene_quad_count() == 0) return best;  // the root is a placeholder
  vec3 inv_dir = safe_inverse(ray.direction);
  int stack_node[BVH_STACK_SIZE];
  float stack_enter[BVH_STACK_SIZE];
  int top = 0;
  BvhNode root = bvh_node(0);
  int node = box_worth_visiting(box_interval(root.lo, root.hi, ray, inv_dir), best.t) ? 0 : -1;
  // The loop ends by its own condition (no node to visit, none stacked), as the trace loop
  // does (trace_common.glsl says why), or at the step cap.
  while (node >= 0 || top > 0) {
    if (node < 0) {
      --top;
      if (stack_enter[top] > best.t) continue;  // a nearer hit was found meanwhile
      node = stack_node[top];
    }
    if (best.steps >= max_steps) {
      best.complete = false;
      break;
    }
    ++best.steps;
    BvhNode n = bvh_node(node);
    if (n.count > 0) {
      for (int i = n.first; i < n.first + n.count; ++i) {
        int ref = bvh_primitive(i);
        float t = scene_primitive_hit(ref, ray, ref < best.ref ? next_float_up(best.t) : best.t);
        if (t != NO_HIT) {
          best.t = t;
          best.ref = ref;
        }
      }
      node = -1;
      continue;
    }
    int a = node + 1;
    int b = n.first;
    BvhNode na = bvh_node(a);
    BvhNode nb = bvh_node(b);
    vec2 ia = box_interval(na.lo, na.hi, ray, inv_dir);
    vec2 ib = box_interval(nb.lo, nb.hi, ray, inv_dir);
    bool hit_a = box_worth_visiting(ia, best.t);
    bool hit_b = box_worth_visiting(ib, best.t);
    if (hit_a && hit_b) {
      bool a_first = ia.x <= ib.x;
      stack_node[top] = a_first ? b : a;
      stack_enter[top] = a_first ? ib.x : ia.x;
      ++top;
      node = a_first ? a : b;
    } else if (hit_a) {
      node = a;
    } else if (hit_b) {
      node = b;
    } else {
      node = -1;
    }
  }
  return best;
}

#endif
