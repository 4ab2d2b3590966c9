// How many samples one draw (or compute dispatch) of the trace shader may take per pixel.
// Mesa 22's llvmpipe (Debian 12's own, Ubuntu 22.04's) ends every loop of a shader invocation,
// fragment or compute, once all its loops together have run 65535 iterations
// (LP_MAX_TGSI_LOOP_ITERATIONS, "shared between every loop"; Mesa 25.0 has no such limit,
// bench/reports/THROUGHPUT.md "Mesa 25"): a pass of many samples then
// silently skips intersection tests and returns garbage or NaN (the default project at 16x16 in
// one pass of 1000 samples, with the shader as it was before its closest-hit loop was unrolled:
// 28% of samples non-finite with either entry point; in passes of 100: none). So the renderer
// splits passes into draws of at most samples_per_draw_for samples, estimated from the loops
// one sample runs (a bound, not a count). Other drivers have no such limit, and the extra draws cost
// them nothing noticeable. A scene whose single sample may exceed the limit (thousands of
// shapes, looped over without an acceleration structure) cannot render correctly on Mesa 22;
// the renderer traces such scenes with the BVH (renderer/bvh.h), whose traversal it caps.
#pragma once

#include <algorithm>

namespace glint {

constexpr long kLlvmpipeLoopLimit = 65535;

// Per bounce: the closest-hit loops of the path ray and of a shadow ray (with a few
// pass-throughs), the light and environment binary searches, the BSDF and light code.
inline long loop_iterations_per_sample(long shapes, int max_bounces) {
  return (max_bounces + 2L) * (3 * (shapes + 2) + 64);
}

// A quarter of the limit per draw, at most 64 samples.
inline int samples_per_draw_for(long per_sample) {
  return static_cast<int>(std::clamp(kLlvmpipeLoopLimit / 4 / std::max(per_sample, 1L), 1L, 64L));
}

// With the BVH (shaders/lib/bvh.glsl) a closest-hit query has no bound below the number of
// nodes (a ray may meet every box), so the shader caps it: at most `steps` node visits, each
// running the traversal loop once, the leaf loop at most kLeafSize times, and one more
// traversal iteration to pop the entry it may have pushed (pushes <= visits), plus the final
// iteration that finds the stack empty: (kLeafSize + 2) * steps + 1 loop iterations. Under
// SIMD execution each lane stops at the cap, so the vector runs a query at most that often too.
// A query that reaches the cap marks its sample, which is then discarded and counted like a
// non-finite one (never added with a wrong hit). In the estimate above, a query counts as a
// loop over that many shapes.
inline long bvh_query_iterations(int steps, int leaf_size) { return (leaf_size + 2L) * steps + 1; }

inline long bvh_loop_iterations_per_sample(int steps, int leaf_size, int max_bounces) {
  return (max_bounces + 2L) * (3 * (bvh_query_iterations(steps, leaf_size) + 2) + 64);
}

// Manifold next-event estimation (shaders/lib/manifold_nee.glsl) counted as this many more
// bounces: it runs at two vertices of a path, each at most 31 scan and 3 x 20 refinement
// iterations, a light pick, and 3 x 3 closest-hit queries for up to three chains. A bounce
// above counts 3 queries and 64 other iterations: 18 queries are 6 bounces' worth, the
// 2 x (91 + the light pick's search) other iterations fewer than 4 bounces' 256.
constexpr int kMneeLoopBounces = 10;
inline int loop_budget_bounces(int max_bounces, bool mnee) { return max_bounces + (mnee ? kMneeLoopBounces : 0); }

// The cap: the most steps that keep one sample (a draw of one sample) within the limit, so that
// on llvmpipe a traversal stops at the cap (and says so) before the driver would stop it
// silently. Rays in a binned-SAH tree visit tens of nodes (unit.Bvh.SameHitAsTheLoop: 8 to 29 on
// average), so the cap of 360 at 8 bounces is rarely reached (gl.hard_LoopLimit.BvhSceneOfTenThousandSpheres
// checks that a 10^4-sphere scene discards no sample). With many bounces the cap would fall below
// kMinBvhSteps; it stays there, and the scene is reported as exceeding the limit. Measured
// (bench/tools/scale.py scenes, 4 bounces, cap 602, 64x64 pixels at 4 spp): at 10^5 spheres one
// sample in 16384 reached it (with a cap of 4000 none did); bench/reports/SCALING.md counts them. Drivers without the limit get
// kMaxBvhSteps (GpuRenderer).
constexpr int kMinBvhSteps = 128;
constexpr int kMaxBvhSteps = 4096;
inline int bvh_max_steps(int leaf_size, int max_bounces) {
  const long per_query = (kLlvmpipeLoopLimit / (max_bounces + 2L) - 64) / 3 - 2;
  return static_cast<int>(std::clamp((per_query - 1) / (leaf_size + 2L), long(kMinBvhSteps), long(kMaxBvhSteps)));
}

}  // namespace glint
