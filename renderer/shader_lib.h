// The shared shader maths (shaders/lib/*.glsl) compiled as C++ (DESIGN.md §5), in float, as
// glint::gpu::*. The same files are compiled by the GPU in the trace shader; the editor's
// picking and the CPU tests use them from here. The prelude below supplies the GLSL names
// that GLM spells differently; the GLSL files use only the common subset.
// GLSL has no `inline`, so the files are included in an anonymous namespace: every translation
// unit gets its own copy (internal linkage) and no definition clashes at link time.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace glint::gpu {

using namespace glm;  // vec3, dot, cross, normalize, clamp, mix, floatBitsToInt, ...
using uint = std::uint32_t;

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-variable"
namespace {
#include "shaders/lib/common.glsl"
#include "shaders/lib/rng.glsl"
#include "shaders/lib/sobol.glsl"
#include "shaders/lib/mapping.glsl"
#include "shaders/lib/sampling.glsl"
#include "shaders/lib/intersect.glsl"
#include "shaders/lib/camera.glsl"
#include "shaders/lib/bsdf.glsl"
#include "shaders/lib/tonemap.glsl"
}  // namespace
#pragma GCC diagnostic pop

}  // namespace glint::gpu
