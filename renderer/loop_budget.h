// How many samples one draw of the trace shader may take per pixel. Mesa's llvmpipe ends every
// loop of a shader invocation once all its loops together have run 65535 iterations
// (LP_MAX_TGSI_LOOP_ITERATIONS, "shared between every loop"): a pass of many samples then
// silently skips intersection tests and returns garbage or NaN (the default project at 16x16 in
// one pass of 1000 samples: 28% of samples non-finite; in passes of 100: none). So the renderer
// splits passes into draws of at most samples_per_draw samples, estimated from the loops one
// sample runs (a bound, not a count). Other drivers have no such limit, and the extra draws cost
// them nothing noticeable. A scene whose single sample may exceed the limit (thousands of
// shapes, looped over without an acceleration structure) cannot render correctly on llvmpipe.
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
inline int samples_per_draw(long shapes, int max_bounces) {
  const long per_sample = loop_iterations_per_sample(shapes, max_bounces);
  return static_cast<int>(std::clamp(kLlvmpipeLoopLimit / 4 / std::max(per_sample, 1L), 1L, 64L));
}

}  // namespace glint
