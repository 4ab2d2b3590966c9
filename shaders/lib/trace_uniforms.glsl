// The uniforms of the trace program (renderer/trace_uniforms.h sets them): the image, the
// sample range, the camera, the environment, next-event estimation, adaptive sampling and
// the sampler choice.
// GLSL only, part of the trace program (shaders/trace_common.glsl includes it after the
// shared maths); not compiled as C++ (renderer/shader_lib.h), since it reads the uniforms,
// tables and samplers of the trace program.

uniform ivec2 u_resolution;
uniform uint u_samples_before;  // samples already in the accumulation
uniform uint u_first_sample;    // the sequence index of the accumulation's first sample (RenderOptions)
uniform int u_samples_per_pass;
uniform uint u_seed;
uniform int u_max_bounces;
uniform int u_sphere_count;
uniform int u_quad_count;
// Closest hits by BVH traversal instead of the loop over every shape (the renderer decides from
// the scene); a traversal visits at most u_bvh_max_steps nodes (renderer/loop_budget.h).
// Specialised programs compile only one of the two (GLINT_NO_BVH, GLINT_NO_LOOP).
uniform bool u_use_bvh;
uniform int u_bvh_max_steps;
uniform vec3 u_cam_origin;
uniform vec3 u_cam_right;
uniform vec3 u_cam_up;
uniform vec3 u_cam_forward;
uniform float u_cam_tan_half_vfov;
uniform float u_cam_aspect;
uniform float u_cam_aperture;
uniform float u_cam_focus;
uniform vec3 u_env_color;  // colour * intensity, or intensity alone when textured
uniform bool u_env_textured;
uniform float u_env_rotation;
// Next-event estimation: u_light_count emitting shapes, picked with probability
// (1 - u_env_select) times their power share; the environment map with u_env_select.
uniform int u_light_count;
uniform float u_env_select;
uniform bool u_russian_roulette;
// Adaptive sampling (docs/DESIGN.md §4.2): once a pixel has u_adaptive_min_samples, a pass
// samples it only if its estimated error per sample taken is at least u_adaptive_threshold,
// or if the pass is one of every u_adaptive_every (so that every pixel keeps sampling).
uniform bool u_adaptive;
uniform float u_adaptive_threshold;
uniform uint u_adaptive_min_samples;
uniform uint u_adaptive_every;
uniform uint u_pass_index;
uniform float u_clamp;  // largest luminance of one sample; 0: off (biased when on)
// Region render (GpuRenderer::set_sample_region): only pixels in [u_region.xy, u_region.zw)
// take samples; the others keep their state. Their counts then differ, so once a region has
// been used since the last reset each pixel continues from its own count (u_per_pixel_counts),
// as with adaptive sampling.
uniform bool u_region_on;
uniform ivec4 u_region;
uniform bool u_per_pixel_counts;
// A transparent background (RenderOptions::transparent_background): a camera ray that finds
// the environment adds nothing (the environment still lights the scene), so the mean is the
// colour premultiplied by the coverage.
uniform bool u_transparent_background;
// Path regeneration's restart policy (add_samples): false, a lane whose path has ended starts
// its next sample at once; true, it waits until no lane of its SIMD group has a path in flight,
// so that the group starts its samples together (renderer/path_restart.h chooses).
uniform bool u_restart_together;
// Owen-scrambled Sobol points instead of independent PCG numbers; a constant in programs for
// one sampler (renderer/shader_features.h), so that the other one's code is left out.
#if defined(GLINT_NO_PCG_SAMPLER)
const bool u_sobol = true;
#elif defined(GLINT_NO_SOBOL_SAMPLER)
const bool u_sobol = false;
#else
uniform bool u_sobol;
#endif
