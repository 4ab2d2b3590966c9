// The shared shader maths (shaders/lib/*.glsl) compiled as C++ (docs/DESIGN.md §8), in float, as
// glint::gpu::*. The same files are compiled by the GPU in the trace shader; the editor's
// picking and the CPU tests use them from here. The prelude below supplies the GLSL names
// that GLM spells differently; the GLSL files use only the common subset.
// GLSL has no `inline`, so the files are included in an anonymous namespace: every translation
// unit gets its own copy (internal linkage) and no definition clashes at link time.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "renderer/bvh.h"
#include "renderer/gpu_scene.h"

namespace glint::gpu {

using namespace glm;  // vec3, dot, cross, normalize, clamp, mix, floatBitsToInt, ...
using uint = std::uint32_t;

// The environment-sampling tables that shaders/lib/environment_sampling.glsl reads through
// accessor functions (a lib file cannot declare buffers): point this at the tables of a
// glint::EnvironmentDistribution (renderer/environment_distribution.h) before calling
// sample_environment or environment_pdf on the CPU. One per thread; the double build of the
// tests reads the same tables.
struct EnvironmentTablesView {
  int width = 0;
  int height = 0;
  const float* marginal_cdf = nullptr;     // height + 1 entries
  const float* conditional_cdf = nullptr;  // height rows of width + 1 entries
};
inline thread_local EnvironmentTablesView environment_tables;

// The scene that shaders/lib/bvh.glsl queries on the CPU (the shader reads the same arrays from
// its table textures): the packed shapes and, for closest_hit_bvh, the hierarchy of
// renderer/bvh.h. One per thread.
struct SceneView {
  const glint::GpuSphere* spheres = nullptr;
  int sphere_count = 0;
  const glint::GpuQuad* quads = nullptr;
  int quad_count = 0;
  const glint::GpuBvhNode* nodes = nullptr;
  const int32_t* primitives = nullptr;
};
inline thread_local SceneView scene_view;

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
#include "shaders/lib/dielectric.glsl"
#include "shaders/lib/bsdf.glsl"
#include "shaders/lib/tonemap.glsl"
#include "shaders/lib/error_estimate.glsl"
#include "shaders/lib/lights.glsl"
ivec2 env_distribution_size() { return ivec2(environment_tables.width, environment_tables.height); }
float env_marginal_cdf(int i) { return environment_tables.marginal_cdf[i]; }
float env_conditional_cdf(int row, int i) {
  return environment_tables.conditional_cdf[std::size_t(row) * (environment_tables.width + 1) + i];
}
#include "shaders/lib/environment_sampling.glsl"
#include "shaders/lib/bvh.glsl"
int scene_sphere_count() { return scene_view.sphere_count; }
int scene_quad_count() { return scene_view.quad_count; }
float scene_sphere_hit(int i, Ray ray, float tmax) {
  vec4 s = scene_view.spheres[i].center_radius;
  return intersect_unit_sphere(ray, vec3(s), s.w, 0.0f, tmax);
}
float scene_quad_hit(int i, Ray ray, float tmax) {
  const glint::GpuQuad& q = scene_view.quads[i];
  return intersect_quad(ray, vec3(q.p0), vec3(q.p1), vec3(q.p2), vec3(q.p3), vec2(q.uv01), vec2(q.uv01.z, q.uv01.w),
                        vec2(q.uv23), vec2(q.uv23.z, q.uv23.w), 0.0f, tmax).t;
}
BvhNode bvh_node(int i) {
  const glint::GpuBvhNode& n = scene_view.nodes[i];
  return BvhNode(n.lo, n.first, n.hi, n.count);
}
int bvh_primitive(int i) { return scene_view.primitives[i]; }
}  // namespace
#pragma GCC diagnostic pop

}  // namespace glint::gpu
