// The uniform block of shaders/unrolled_loop.glsl: a scene of few shapes is traced by a program
// compiled for exactly its numbers of spheres and quads, whose closest-hit loop is unrolled and
// reads each shape from this block at a constant offset (one load for all SIMD lanes on
// llvmpipe, instead of a per-lane table fetch; bench/reports/THROUGHPUT.md measures it). No GL here.
#pragma once

#include <vector>

#include "renderer/gpu_scene.h"

namespace glint {

// Shapes of each kind the block holds, and the most for which a program is compiled with the
// loop unrolled: Mesa unrolls at most max_unroll_iterations (32 on llvmpipe) iterations.
// The block's declaration in shaders/unrolled_loop.glsl has this size.
constexpr int kLoopShapesMax = 32;
// The uniform-block binding of the block (shaders/unrolled_loop.glsl).
constexpr unsigned kLoopShapesBinding = 0;

// The block's bytes: std140 lays out arrays of these structs of vec4s as std430 does.
struct LoopShapesBlock {
  GpuSphere spheres[kLoopShapesMax] = {};
  GpuQuad quads[kLoopShapesMax] = {};
};
static_assert(sizeof(GpuSphere) == 32 && sizeof(GpuQuad) == 128, "std140 strides of the block");

// Whether a scene of `spheres` and `quads` traced by the loop (not the BVH) gets a program with
// the loop unrolled.
bool unrolls_loop(long spheres, long quads);

// The block for the packed scene: its first kLoopShapesMax spheres and quads, zeros after.
LoopShapesBlock loop_shapes_block(const std::vector<GpuSphere>& spheres,
                                  const std::vector<GpuQuad>& quads);

}  // namespace glint
