// The path tracer shared by the fragment-shader and the compute-shader entry points
// (shaders/trace.frag, shaders/trace.comp; docs/DESIGN.md §3.3): uniforms, buffers, samplers,
// continue_path and add_samples, one copy (the GLSL-only parts in shaders/lib included below),
// so that both draw the same random numbers and give the same image. Included after the entry point's #version line and the `#define GLINT_NO_...`
// lines that renderer/shader_features.cpp inserts for what the scene lacks (none defined is
// the generic program).
// Accumulation texel: rgb = mean of the finite samples so far, a = count of samples discarded
// (non-finite, or cut short by the BVH step cap); compensation texel: rgb = the low-order part
// of the mean that float32 could not hold (Kahan), a = samples this pixel has taken (finite and
// discarded; below u_samples_before only with adaptive sampling). Variance texel: rgb = mean
// squared deviation of the finite samples from their mean (M2 / n, Chan et al.'s pairwise
// update), its compensation texel: rgb what float32 could not hold of it; a unused in both.
// The error estimate (shaders/error_reduce.frag, docs/DESIGN.md §4.1) is computed from them.
// The variance texel's a counts the finite samples whose camera ray hit a surface (not the
// environment; seen through cut-outs counts as the environment): a / finite samples is the
// pixel's coverage, the alpha of a transparent-background output (renderer/render_output.h).
// Next-event estimation samples emitting shapes and an environment map; with neither there is
// nothing to sample (u_light_count and u_env_select are 0) and its code is left out.
#if defined(GLINT_NO_EMITTERS) && defined(GLINT_NO_ENV_TEXTURE)
#define GLINT_NO_LIGHT_SAMPLING
#endif
#include "lib/common.glsl"
#include "lib/rng.glsl"
#include "lib/sobol.glsl"
#include "lib/error_estimate.glsl"
#include "lib/mapping.glsl"
#include "lib/sampling.glsl"
#include "lib/intersect.glsl"
#include "lib/camera.glsl"
#include "lib/dielectric.glsl"
#include "lib/bsdf.glsl"
#include "lib/lights.glsl"
#include "lib/bvh.glsl"
// The trace program's own parts (GLSL only), in dependency order.
#include "lib/trace_scene_tables.glsl"
#include "lib/trace_uniforms.glsl"
#include "lib/trace_random.glsl"
#include "lib/trace_textures.glsl"
#include "lib/scene_intersection.glsl"
#include "lib/surface_material.glsl"
#include "lib/next_event_estimation.glsl"
#if defined(GLINT_MNEE)  // scenes with caustics through smooth spheres (renderer/shader_features.h)
#include "lib/manifold_nee.glsl"
#endif
#include "lib/path_continuation.glsl"
#include "lib/sample_accumulation.glsl"
