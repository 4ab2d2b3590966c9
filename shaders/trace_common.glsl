// The path tracer shared by the fragment-shader and the compute-shader entry points
// (shaders/trace.frag, shaders/trace.comp; docs/DESIGN.md §3.3): uniforms, buffers, samplers,
// continue_path and add_samples, one copy, so that both draw the same random numbers and give the
// same image. Included after the entry point's #version line and the `#define GLINT_NO_...`
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

struct GpuSphere {
  vec4 center_radius;
  ivec4 material;  // x: material index
};
struct GpuQuad {
  vec4 p0;
  vec4 p1;
  vec4 p2;
  vec4 p3;
  vec4 uv01;       // uv0.xy, uv1.xy
  vec4 uv23;       // uv2.xy, uv3.xy
  vec4 normal;     // xyz: geometric normal
  ivec4 material;  // x: material index
};
struct GpuMaterial {
  vec4 color;     // rgb colour, a: type
  vec4 emission;  // rgb
  vec4 params;    // roughness, ior, opacity
  ivec4 layers;   // texture layers of colour, emission, roughness; -1 for none
};

struct GpuLight {
  ivec4 shape;   // x: 0 sphere, 1 quad; y: its index; z: 1 for a parallelogram quad
  vec4 select;   // x: pdf of picking it, y: cdf, z: a quad's area
};

// The samplers, in a fixed order: each is given the next sampler slot in declaration order
// (after the entry point's own), and every one is read in every program (every_sampler, behind a
// uniform that is never set), so that a slot holds the same sampler in every specialised
// program. The reason is llvmpipe: it keys a compiled shader by the sampler state in each slot
// it reads, and Mesa leaves a buffer texture's slot as the last draw of any program set it. The
// buffer textures come last, on slots that no 2-D sampler of any program takes, so that their
// state is the same in the editor's context and in the worker's (program_worker.h), and the
// worker's warm-up draw compiles what the editor's first draw needs.
layout(binding = 2) uniform sampler2D u_environment;
// The textures' texels, row after row (lib/mapping.glsl's texel_index is the position).
layout(binding = 1) uniform sampler2D u_texels_8bit;   // RGBA8, as stored
layout(binding = 4) uniform sampler2D u_texels_float;  // RGBA32F
const int TEXEL_ROW_SHIFT = 14;  // 16384 texels a row (GpuRenderer::kTexelRowWidth)
ivec2 texel_position(int texel) {
  return ivec2(texel & ((1 << TEXEL_ROW_SHIFT) - 1), texel >> TEXEL_ROW_SHIFT);
}

// The scene's tables (renderer/gpu_scene.h, renderer/bvh.h, renderer/environment_distribution.h):
// their std430 bytes in integer buffer textures (RGBA32I, 16 bytes a texel, or R32I for the
// lists of ints and floats; a float is intBitsToFloat of its texel, every bit kept); texture
// unit 7 + k holds the renderer's table k (GpuRenderer::upload_table). Why not storage buffers:
// on llvmpipe a storage-buffer read is a loop over the SIMD group's lanes with a branch per lane
// and component, a texel fetch one gather, and a buffer texture's fetch is cheaper than a 2-D
// texture's (bench/reports/THROUGHPUT.md).
layout(binding = 7) uniform isamplerBuffer u_sphere_table;          // GpuSphere: 2 texels
layout(binding = 8) uniform isamplerBuffer u_quad_table;            // GpuQuad: 8 texels
layout(binding = 9) uniform isamplerBuffer u_material_table;        // GpuMaterial: 4 texels
layout(binding = 10) uniform isamplerBuffer u_texture_layer_table;  // ivec4, see lib/mapping.glsl
layout(binding = 11) uniform isamplerBuffer u_light_table;          // GpuLight: 2 texels
layout(binding = 12) uniform isamplerBuffer u_env_cdf_table;        // float (R32I)
layout(binding = 13) uniform isamplerBuffer u_bvh_node_table;       // BvhNode: 2 texels
layout(binding = 14) uniform isamplerBuffer u_bvh_primitive_table;  // int (R32I)

ivec4 table_texel(isamplerBuffer table, int texel) { return texelFetch(table, texel); }
vec4 table_vec4(isamplerBuffer table, int texel) {
  return intBitsToFloat(table_texel(table, texel));
}

// Never set (false): its only use is that every sampler above is read in every program.
uniform bool u_read_every_sampler;
vec4 every_sampler() {
  return texelFetch(u_environment, ivec2(0), 0) + texelFetch(u_texels_8bit, ivec2(0), 0) +
         texelFetch(u_texels_float, ivec2(0), 0) +
         vec4(texelFetch(u_sphere_table, 0) + texelFetch(u_quad_table, 0) +
              texelFetch(u_material_table, 0) + texelFetch(u_texture_layer_table, 0) +
              texelFetch(u_light_table, 0) + texelFetch(u_env_cdf_table, 0) +
              texelFetch(u_bvh_node_table, 0) + texelFetch(u_bvh_primitive_table, 0));
}
// Element i of a table; the compiler drops the fetches of fields that are not used.
GpuSphere sphere_at(int i) {
  return GpuSphere(table_vec4(u_sphere_table, 2 * i), table_texel(u_sphere_table, 2 * i + 1));
}
GpuQuad quad_at(int i) {
  int k = 8 * i;
  return GpuQuad(table_vec4(u_quad_table, k), table_vec4(u_quad_table, k + 1),
                 table_vec4(u_quad_table, k + 2), table_vec4(u_quad_table, k + 3),
                 table_vec4(u_quad_table, k + 4), table_vec4(u_quad_table, k + 5),
                 table_vec4(u_quad_table, k + 6), table_texel(u_quad_table, k + 7));
}
GpuMaterial material_at(int i) {
  int k = 4 * i;
  return GpuMaterial(table_vec4(u_material_table, k), table_vec4(u_material_table, k + 1),
                     table_vec4(u_material_table, k + 2), table_texel(u_material_table, k + 3));
}
GpuLight light_at(int i) {
  return GpuLight(table_texel(u_light_table, 2 * i), table_vec4(u_light_table, 2 * i + 1));
}

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

// The sample's random numbers. PCG: one hashed stream per (pixel, sample, seed), read in
// order. Sobol: the sample's point in a given dimension of the pixel's scrambled sequence (1-D
// and 2-D dimensions are scrambled independently, sobol.glsl). Dimensions are laid out by
// purpose so that every sample uses the same one for the same decision (a dimension shared by
// different decisions in different samples loses its stratification): 0 and 1 the pixel and
// lens positions (2-D; the pixel's shares a 4-D point with the first light point, g_primary),
// then DIMENSIONS_PER_BOUNCE per bounce (light_dimension and so on).
// Decisions that are taken only sometimes (coverage, roulette) use the PCG stream.
uint g_rng;
uint g_sample_index;
uint g_pixel_seed;
// Sobol: one 4-D point (sobol_sample_4d) for the two first decisions that interact, the light
// point at the first vertex (xy: Sobol dimensions 0 and 1, a (0,2)-sequence) and the position
// in the pixel (zw: dimensions 2 and 3, a (0,4,2)-net at 16 samples and t <= 2 for every
// power-of-two prefix up to 256), so that the light's visibility and distance, which change
// across the pixel, are integrated over a 4-D net (Burley 2020); the other decisions are
// padded (their own shuffled and scrambled pairs).
vec4 g_primary;
float rand() {
  g_rng = rng_advance(g_rng);
  return rng_to_unit_float(g_rng);
}
const uint DIMENSIONS_PER_BOUNCE = 2u;
uint light_dimension(int bounce) { return 2u + DIMENSIONS_PER_BOUNCE * uint(bounce); }
uint bsdf_dimension(int bounce) { return light_dimension(bounce) + 1u; }
float sample_1d(uint dimension) {
  if (u_sobol) return sobol_sample_1d(g_sample_index, g_pixel_seed, dimension);
  return rand();
}
vec2 sample_2d(uint dimension) {
  if (u_sobol) {
    if (dimension == 0u) return g_primary.zw;
    if (dimension == light_dimension(0)) return g_primary.xy;
    return sobol_sample_2d(g_sample_index, g_pixel_seed, dimension);
  }
  float a = rand();
  return vec2(a, rand());
}

#if !defined(GLINT_NO_TEXTURES)
vec4 fetch_texel(ivec4 layer, int x, int y) {
  int i = texel_index(layer, x, y);
  if (layer.w == TEXELS_FLOAT) return texelFetch(u_texels_float, texel_position(i), 0);
  vec4 t = texelFetch(u_texels_8bit, texel_position(i), 0);
  if (layer.w == TEXELS_8BIT_SRGB) t.rgb = vec3(srgb_decode(t.r), srgb_decode(t.g), srgb_decode(t.b));
  return t;
}
#endif

vec4 texture_lookup(int layer, vec2 uv) {
#if defined(GLINT_NO_TEXTURES)
  return vec4(1.0);  // no used material has a texture: every layer is -1
#else
  if (layer < 0) return vec4(1.0);
  ivec4 l = table_texel(u_texture_layer_table, layer);
  BilinearTaps taps = bilinear_taps(uv, l.xy);
  vec4 a = fetch_texel(l, taps.texels.x, taps.texels.y);
  vec4 b = fetch_texel(l, taps.texels.z, taps.texels.y);
  vec4 c = fetch_texel(l, taps.texels.x, taps.texels.w);
  vec4 d = fetch_texel(l, taps.texels.z, taps.texels.w);
  return mix(mix(a, b, taps.weight.x), mix(c, d, taps.weight.x), taps.weight.y);
#endif
}

vec3 environment(vec3 d) {
#if !defined(GLINT_NO_ENV_TEXTURE)
  if (u_env_textured) return u_env_color * texture(u_environment, environment_uv(d, u_env_rotation)).rgb;
#endif
  return u_env_color;
}

// Importance sampling of the environment map: the tables of
// renderer/environment_distribution.h, read by lib/environment_sampling.glsl.
uniform ivec2 u_env_distribution_size;
ivec2 env_distribution_size() { return u_env_distribution_size; }
float env_cdf(int i) { return intBitsToFloat(table_texel(u_env_cdf_table, i).x); }
float env_marginal_cdf(int i) { return env_cdf(i); }
float env_conditional_cdf(int row, int i) {
  return env_cdf(u_env_distribution_size.y + 1 + row * (u_env_distribution_size.x + 1) + i);
}
#include "lib/environment_sampling.glsl"

struct SceneHit {
  float t;
  vec3 position;  // on the surface to a few ulps of error_scale (not o + t d)
  float error_scale;  // coordinate magnitude of the shape (see surface_offset_distance)
  vec3 normal;  // geometric, unit, not yet flipped
  vec2 uv;
  int material;
  int light;  // index into lights[] when the shape emits, else -1
};

// The scene as shaders/lib/bvh.glsl reads it.
int scene_sphere_count() { return u_sphere_count; }
int scene_quad_count() { return u_quad_count; }
// The nearest hit in (0, tmax) of a sphere or a quad, or NO_HIT (every ray the tracer spawns has
// a unit direction).
float sphere_hit(vec4 center_radius, Ray ray, float tmax) {
  return intersect_unit_sphere(ray, center_radius.xyz, center_radius.w, 0.0, tmax);
}
float quad_hit(GpuQuad q, Ray ray, float tmax) {
#if defined(GLINT_NO_GENERAL_QUADS)
  // Every quad is planar and convex: intersect_planar_quad's two steps.
  float t = planar_quad_plane_t(ray, q.p0.xyz, q.normal.xyz, 0.0, tmax);
  if (t == NO_HIT) return NO_HIT;
  if (!planar_quad_inside_edges(ray, q.p0.xyz, q.p1.xyz, q.p2.xyz, q.p3.xyz)) return NO_HIT;
  return t;
#else
  return intersect_quad(ray, q.p0.xyz, q.p1.xyz, q.p2.xyz, q.p3.xyz, q.uv01.xy, q.uv01.zw,
                        q.uv23.xy, q.uv23.zw, 0.0, tmax).t;
#endif
}
float scene_sphere_hit(int i, Ray ray, float tmax) {
  return sphere_hit(sphere_at(i).center_radius, ray, tmax);
}
float scene_quad_hit(int i, Ray ray, float tmax) { return quad_hit(quad_at(i), ray, tmax); }
#if defined(GLINT_LOOP_SPHERES)
#include "unrolled_loop.glsl"
#endif
BvhNode bvh_node(int i) {
  ivec4 a = table_texel(u_bvh_node_table, 2 * i);
  ivec4 b = table_texel(u_bvh_node_table, 2 * i + 1);
  return BvhNode(intBitsToFloat(a.xyz), a.w, intBitsToFloat(b.xyz), b.w);
}
int bvh_primitive(int i) { return table_texel(u_bvh_primitive_table, i).x; }

// Set when this sample's camera ray found the environment (after any cut-outs it passed).
bool g_primary_escaped;
// Set when a BVH traversal of this sample stopped at its step cap: the sample is discarded
// (counted with the non-finite ones) rather than added with a possibly wrong hit.
bool g_incomplete;

PrimitiveHit closest_primitive(Ray ray) {
#if defined(GLINT_LOOP_SPHERES)
  return closest_hit_unrolled(ray, 1e30);
#elif defined(GLINT_NO_BVH)
  return closest_hit_loop(ray, 1e30);
#else
#if !defined(GLINT_NO_LOOP)
  if (!u_use_bvh) return closest_hit_loop(ray, 1e30);
#endif
  PrimitiveHit h = closest_hit_bvh(ray, 1e30, u_bvh_max_steps);
  if (!h.complete) g_incomplete = true;
  return h;
#endif
}

SceneHit intersect_scene(Ray ray) {
  SceneHit hit = SceneHit(1e30, vec3(0.0), 0.0, vec3(0.0), vec2(0.0), -1, -1);
  PrimitiveHit closest = closest_primitive(ray);
  if (closest.ref < 0) return hit;
  hit.t = closest.t;
#if !defined(GLINT_NO_QUADS)
#if !defined(GLINT_NO_SPHERES)
  if (closest.ref >= u_sphere_count)
#endif
  {
    GpuQuad q = quad_at(closest.ref - u_sphere_count);
    // The quad's nearest hit again, for its texture coordinates and point (the same t: the
    // test's result does not depend on tmax beyond it).
    QuadHit h = intersect_quad(ray, q.p0.xyz, q.p1.xyz, q.p2.xyz, q.p3.xyz, q.uv01.xy, q.uv01.zw,
                               q.uv23.xy, q.uv23.zw, 0.0, 1e30);
    hit.uv = h.uv;
    hit.position = h.t != NO_HIT ? h.position : ray.origin + hit.t * ray.direction;
    hit.normal = q.normal.xyz;
    hit.error_scale = quad_error_scale(q.p0.xyz, q.p1.xyz, q.p2.xyz, q.p3.xyz);
    hit.material = q.material.x;
    hit.light = q.material.y;
  }
#endif
#if !defined(GLINT_NO_QUADS) && !defined(GLINT_NO_SPHERES)
  else
#endif
#if !defined(GLINT_NO_SPHERES)
  {
    GpuSphere sphere = sphere_at(closest.ref);
    vec4 s = sphere.center_radius;
    hit.position = sphere_hit_point(ray, hit.t, s.xyz, s.w);
    hit.error_scale = sphere_error_scale(s.xyz, s.w);
    hit.normal = normalize(hit.position - s.xyz);
    hit.uv = direction_to_uv(hit.normal);
    hit.material = sphere.material.x;
    hit.light = sphere.material.y;
  }
#endif
  return hit;
}

// Coverage pass-throughs allowed per path: a stack of cut-out surfaces deeper than this
// is treated as opaque at the last one.
const int MAX_PASS_THROUGH = 64;
// Russian roulette starts after this many bounces (the first ones carry most of the light), as
// Mitsuba 3's rr_depth; bench/reports/THROUGHPUT.md compares it with an earlier start.
const int ROULETTE_START = 5;

vec3 material_emission(GpuMaterial gm, vec2 uv) {
  return gm.emission.rgb * texture_lookup(gm.layers.y, uv).rgb;
}

SurfaceMaterial surface_material(GpuMaterial gm, vec4 color_tex, vec2 uv) {
  return SurfaceMaterial(int(gm.color.a), gm.color.rgb * color_tex.rgb,
                         gm.params.x * texture_lookup(gm.layers.z, uv).r, gm.params.y);
}

// What a ray passes straight through at a surface, on average: the uncovered fraction, and of
// the covered one what smooth thin glass transmits (it does not bend rays). The path tracer
// makes the same choices at random, so shadow rays and BSDF paths agree in expectation.
// Refractive surfaces bend every ray that crosses them, so they block shadow rays (light
// through them arrives by BSDF sampling alone, as in Mitsuba's `path` integrator).
vec3 straight_transmittance(GpuMaterial gm, vec4 color_tex, vec2 uv, float coverage, float cos_theta) {
  vec3 t = vec3(1.0 - coverage);
  // Most blockers are opaque: only glass needs its roughness (a texture fetch) looked up.
  if (int(gm.color.a) != MATERIAL_TRANSPARENT) return t;
  SurfaceMaterial m = surface_material(gm, color_tex, uv);
  if (is_delta_material(m)) {
    t += coverage * (1.0 - fresnel_schlick(dielectric_f0(m.ior), cos_theta)) * m.color;
  }
  return t;
}

// The solid-angle pdf with which next-event estimation at p picks the point y of light i.
float light_pdf(int i, vec3 p, vec3 y) {
  GpuLight l = light_at(i);
  float shape_pdf = 0.0;
#if !defined(GLINT_NO_SPHERES)
  if (l.shape.x == 0) {
    vec4 s = sphere_at(l.shape.y).center_radius;
    shape_pdf = sphere_light_pdf(p, s.xyz, s.w, y);
  }
#endif
#if !defined(GLINT_NO_QUADS)
  if (l.shape.x != 0) {
    GpuQuad q = quad_at(l.shape.y);  // only the texels read are fetched
#if !defined(GLINT_NO_GENERAL_QUAD_LIGHTS)
    if (l.shape.z == 0) shape_pdf = quad_light_pdf(p, q.p0.xyz, q.p1.xyz, q.p2.xyz, q.p3.xyz, y);
    else
#endif
      shape_pdf = parallelogram_light_pdf(p, q.p0.xyz, q.normal.xyz, l.select.z, y);
  }
#endif
  return (1.0 - u_env_select) * l.select.x * shape_pdf;
}

// The light whose cdf interval holds u (binary search: scenes may hold many emitters).
int pick_light(float u) {
  int lo = 0;
  int hi = u_light_count - 1;
  while (lo < hi) {
    int mid = (lo + hi) / 2;
    if (u < light_at(mid).select.y) hi = mid;
    else lo = mid + 1;
  }
  return lo;
}

// The material of primitive `ref` of a closest hit: x its index, y its light's (-1: none).
ivec4 primitive_material(int ref) {
#if !defined(GLINT_NO_QUADS) && !defined(GLINT_NO_SPHERES)
  return ref >= u_sphere_count ? quad_at(ref - u_sphere_count).material : sphere_at(ref).material;
#elif !defined(GLINT_NO_QUADS)
  return quad_at(ref - u_sphere_count).material;
#else
  return sphere_at(ref).material;
#endif
}

#if defined(GLINT_NO_COVERAGE) && defined(GLINT_NO_TRANSPARENT)
// Radiance reaching `origin` along wi from light `target` (-1: the environment) in a scene
// where every surface blocks light (refractive ones too): the first surface met decides. The
// general loop below gives the same value here, but llvmpipe runs every branch of it whether a
// pixel takes it or not. Without textures only which primitive was hit matters, not where, so
// the hit record (point, normal, uv) is not built either.
vec3 shadow_ray(vec3 origin, vec3 wi, int target) {
  Ray ray = Ray(origin, wi);
#if defined(GLINT_NO_TEXTURES)
  PrimitiveHit closest = closest_primitive(ray);
  if (closest.ref < 0) return target < 0 ? environment(wi) : vec3(0.0);
  ivec4 material = primitive_material(closest.ref);
  if (target < 0 || material.y != target) return vec3(0.0);
  return material_at(material.x).emission.rgb;
#else
  SceneHit hit = intersect_scene(ray);
  if (hit.material < 0) return target < 0 ? environment(wi) : vec3(0.0);
  if (target < 0 || hit.light != target) return vec3(0.0);
  return material_emission(material_at(hit.material), hit.uv);
#endif
}
#else
// Radiance reaching `origin` along wi from light `target` (-1: the environment), through
// cut-outs and smooth thin glass; 0 when anything else blocks it.
vec3 shadow_ray(vec3 origin, vec3 wi, int target) {
  Ray ray = Ray(origin, wi);
  vec3 transmittance = vec3(1.0);
  for (int passes = 0; passes <= MAX_PASS_THROUGH; ++passes) {
    SceneHit hit = intersect_scene(ray);
    if (hit.material < 0) return target < 0 ? transmittance * environment(wi) : vec3(0.0);
    GpuMaterial gm = material_at(hit.material);
    vec4 color_tex = texture_lookup(gm.layers.x, hit.uv);
    float coverage = gm.params.z * color_tex.a;
#if !defined(GLINT_NO_EMITTERS)
    if (target >= 0 && hit.light == target) {
      return transmittance * coverage * material_emission(gm, hit.uv);
    }
#endif
    vec3 n = dot(hit.normal, wi) <= 0.0 ? hit.normal : -hit.normal;  // towards the ray's origin
    transmittance *= straight_transmittance(gm, color_tex, hit.uv, coverage, dot(n, -wi));
    if (max_component(transmittance) <= 0.0) break;
    ray.origin = offset_surface_point(hit.position, -n, hit.error_scale);
  }
  return vec3(0.0);
}
#endif

// A light sample seen from `origin`: the point the shadow ray actually starts from.
LightSample sample_light(int i, vec3 origin, vec2 u) {
  GpuLight l = light_at(i);
#if !defined(GLINT_NO_SPHERES) || defined(GLINT_NO_QUADS)  // (with neither shape, never called)
#if !defined(GLINT_NO_QUADS)
  if (l.shape.x == 0)
#endif
  {
    vec4 s = sphere_at(l.shape.y).center_radius;
    return sample_sphere_light(origin, s.xyz, s.w, u);
  }
#endif
#if !defined(GLINT_NO_QUADS)
  GpuQuad q = quad_at(l.shape.y);
#if !defined(GLINT_NO_GENERAL_QUAD_LIGHTS)
  if (l.shape.z == 0) return sample_quad_light(origin, q.p0.xyz, q.p1.xyz, q.p2.xyz, q.p3.xyz, u);
#endif
  return sample_parallelogram_light(origin, q.p0.xyz, q.p1.xyz, q.p2.xyz, q.normal.xyz, l.select.z, u);
#endif
}

// One light sample at a non-delta vertex, weighted against BSDF sampling (power heuristic;
// Veach 1997, ch. 9). Returns f |cos| Li w / pdf. The light is sampled from the offset origin
// of the shadow ray, not from p: on shapes far from the origin the offset is large (16 float
// epsilons of 1e5 is 0.19), and a direction chosen from p but traced from the offset point
// would miss the edges of the light it aimed at (biased). BSDF rays record the same origin
// (last_p in continue_path), so both strategies see the light from the same point.
vec3 direct_light(SurfaceMaterial m, vec3 p, vec3 n, vec3 wo, float error_scale, int bounce) {
  float u_pick = sample_1d(light_dimension(bounce));
  vec2 u = sample_2d(light_dimension(bounce));
  vec3 above = offset_surface_point(p, n, error_scale);
  vec3 wi;
  float pdf;
  int target;
  vec3 origin = above;
#if !defined(GLINT_NO_ENV_TEXTURE)
  if (u_pick < u_env_select) {
    EnvironmentSample es = sample_environment(u, u_env_rotation);
    if (!es.valid || !(es.pdf > 0.0)) return vec3(0.0);
    wi = es.wi;
    pdf = u_env_select * es.pdf;
    target = -1;
    if (dot(wi, n) <= 0.0) origin = offset_surface_point(p, -n, error_scale);
  }
#endif
#if !defined(GLINT_NO_EMITTERS) && !defined(GLINT_NO_ENV_TEXTURE)
  else
#endif
#if !defined(GLINT_NO_EMITTERS)
  {
    target = pick_light((u_pick - u_env_select) / (1.0 - u_env_select));
    LightSample ls = sample_light(target, above, u);
    if ((m.type == MATERIAL_TRANSPARENT || m.type == MATERIAL_REFRACTIVE) && ls.valid && dot(ls.wi, n) <= 0.0) {
      // Rough glass also transmits: the light is below, seen from below.
      origin = offset_surface_point(p, -n, error_scale);
      ls = sample_light(target, origin, u);
      if (dot(ls.wi, n) >= 0.0) return vec3(0.0);
    }
    if (!ls.valid) return vec3(0.0);
    wi = ls.wi;
    pdf = (1.0 - u_env_select) * light_at(target).select.x * ls.pdf;
  }
#endif
  vec3 f = eval_bsdf(m, n, wo, wi);
  if (max_component(f) <= 0.0) return vec3(0.0);
  vec3 li = shadow_ray(origin, wi, target);
  if (max_component(li) <= 0.0) return vec3(0.0);
  return f * li * (power_heuristic(pdf, pdf_bsdf(m, n, wo, wi)) / pdf);
}

// A path in flight: what continue_path carries from one bounce to the next.
struct PathState {
  Ray ray;
  vec3 radiance;
  vec3 throughput;
  int bounces;
  int passes;  // pass-throughs of cut-outs so far (not bounces)
  // The last scattering vertex: where next-event estimation would have sampled the light that
  // a BSDF-sampled ray finds, for the MIS weight. Camera rays and delta lobes get weight 1.
  vec3 last_p;
  float last_pdf;
  bool last_delta;
  // The product of eta^2 over the refractions so far: a refracted ray's weight carries 1 / eta^2
  // (lib/dielectric.glsl), which the roulette undoes, so that a path inside glass is not killed
  // for a scale it loses again on the way out (pbrt-v4's etaScale; Mitsuba 3 does the same).
  float eta_scale;
};

PathState start_path(Ray ray) {
  return PathState(ray, vec3(0.0), vec3(1.0), 0, 0, ray.origin, 0.0, true, 1.0);
}

// Whether next-event estimation has anything to sample: emitting shapes or an environment map.
bool light_sampling_on() {
#if defined(GLINT_NO_LIGHT_SAMPLING)
  return false;
#else
  return u_light_count > 0 || u_env_select > 0.0;
#endif
}

// One closest-hit query of the path and what follows from it: the emission or environment it
// finds, next-event estimation and the BSDF sample of the next ray. Returns false when the path
// has ended (its radiance is then final).
bool continue_path(inout PathState path) {
  bool light_sampling = light_sampling_on();
  Ray ray = path.ray;
  SceneHit hit = intersect_scene(ray);
  if (hit.material < 0) {
    float w = 1.0;
#if !defined(GLINT_NO_ENV_TEXTURE)  // without an environment map u_env_select is 0
    if (!path.last_delta && u_env_select > 0.0) {
      w = power_heuristic(path.last_pdf, u_env_select * environment_pdf(ray.direction, u_env_rotation));
    }
#endif
    if (path.bounces == 0) g_primary_escaped = true;
    if (!(u_transparent_background && path.bounces == 0))
      path.radiance += path.throughput * environment(ray.direction) * w;
    return false;
  }
  GpuMaterial gm = material_at(hit.material);
  vec3 p = hit.position;
  vec3 wo = -ray.direction;
  vec3 n = dot(hit.normal, wo) >= 0.0 ? hit.normal : -hit.normal;
  vec4 color_tex = texture_lookup(gm.layers.x, hit.uv);
#if !defined(GLINT_NO_COVERAGE)  // without it coverage is 1: no test, and no rand() either
  float coverage = gm.params.z * color_tex.a;
  if (coverage < 1.0 && path.passes < MAX_PASS_THROUGH && rand() >= coverage) {
    // Not a bounce: the ray continues unchanged past the surface.
    path.ray.origin = offset_surface_point(p, -n, hit.error_scale);
    ++path.passes;
    return true;
  }
#endif
#if !defined(GLINT_NO_EMITTERS)
  // Emission found by BSDF sampling, weighted against next-event estimation of the same
  // light from last_p. Shapes that are not lights (no estimated power) keep weight 1.
  float w = 1.0;
  if (hit.light >= 0 && !path.last_delta && u_light_count > 0) {
    w = power_heuristic(path.last_pdf, light_pdf(hit.light, path.last_p, p));
  }
  path.radiance += path.throughput * material_emission(gm, hit.uv) * w;
#endif
  if (path.bounces >= u_max_bounces) return false;
  SurfaceMaterial m = surface_material(gm, color_tex, hit.uv);
#if !defined(GLINT_NO_REFRACTIVE)
  // A refractive surface's inside is a sphere's ball and the side of a quad opposite its
  // geometric normal: a ray arriving from there leaves the material (relative index 1 / ior).
  if (m.type == MATERIAL_REFRACTIVE && dot(hit.normal, wo) < 0.0) m.ior = 1.0 / m.ior;
#endif
  bool delta = is_delta_material(m);
#if !defined(GLINT_NO_LIGHT_SAMPLING)
  if (light_sampling && !delta) {
    path.radiance += path.throughput * direct_light(m, p, n, wo, hit.error_scale, path.bounces);
  }
#endif
  float u_lobe = sample_1d(bsdf_dimension(path.bounces));
  vec2 u = sample_2d(bsdf_dimension(path.bounces));
  BsdfSample s = sample_bsdf(m, n, wo, u_lobe, u);
  if (!s.valid) return false;
  path.throughput *= s.weight;
  if (max_component(path.throughput) <= 0.0) return false;
  // Smooth thin glass passing a ray straight on is not a new vertex for MIS: the light it
  // finds is the one next-event estimation at last_p aimed at, along the same direction.
  // (A refractive surface bends the ray and blocks shadow rays: its delta lobes are vertices
  // with last_delta, so the light they find has weight 1.)
  path.ray = Ray(offset_surface_point(p, dot(s.wi, n) > 0.0 ? n : -n, hit.error_scale), s.wi);
#if !defined(GLINT_NO_REFRACTIVE)
  if (m.type == MATERIAL_REFRACTIVE && dot(s.wi, n) < 0.0) path.eta_scale *= m.ior * m.ior;
#endif
  if (!(s.delta && dot(s.wi, n) < 0.0 && m.type == MATERIAL_TRANSPARENT)) {
    path.last_p = path.ray.origin;
    path.last_pdf = s.pdf;
    path.last_delta = s.delta;
  }
  ++path.bounces;
  if (u_russian_roulette && path.bounces >= ROULETTE_START) {
    // Survive with probability max(throughput) eta_scale (at most 1); survivors carry 1/q more.
    float q = min(1.0, max_component(path.throughput) * path.eta_scale);
    if (rand() >= q) return false;
    path.throughput /= q;
  }
  return true;
}

// Whether adaptive sampling adds samples to this pixel in this pass. The allocation that
// minimises the image's summed error for a sample budget gives each pixel samples in proportion
// to its standard deviation (the Neyman allocation of stratified sampling, Cochran, "Sampling
// Techniques", 3rd ed., §5.5); at that optimum every pixel's error per sample, relMSE / n, is
// the same, so a pixel above the image's mean of it (u_adaptive_threshold, from the last
// estimate) needs samples and one below it waits, as Cycles' adaptive sampling lets converged
// pixels wait. Unlike Cycles none waits forever: every u_adaptive_every-th pass samples all, so
// each pixel's count grows without bound and the image stays consistent.
bool adaptive_pixel_active(vec4 accumulation, vec4 compensation, vec3 variance) {
  if (!u_adaptive) return true;
  float taken = compensation.a;
  if (taken < float(u_adaptive_min_samples) || u_pass_index % u_adaptive_every == 0u) return true;
  float finite = taken - accumulation.a;
  float r = estimated_pixel_relmse(accumulation.rgb, variance, finite);
  return r < 0.0 || r / finite >= u_adaptive_threshold;  // no estimate yet: sample
}

// Sets the per-sample random state of sample `index` (of the pixel's sequence, before
// u_first_sample) and returns its camera path.
PathState start_sample(CameraFrame cam, ivec2 pixel, uint index) {
  g_sample_index = u_first_sample + index;
  g_rng = rng_seed(uint(pixel.x), uint(pixel.y), g_sample_index, u_seed);
  // Without next-event estimation there is no first light point to pair the pixel position
  // with: the pixel takes a 2-D point (Sobol dimensions 0 and 1, a (0,2)-sequence) and the 4-D
  // point's two costlier dimensions are not computed.
  if (u_sobol) {
    g_primary = light_sampling_on() ? sobol_sample_4d(g_sample_index, g_pixel_seed, 0u)
                                    : vec4(0.0, 0.0, sobol_sample_2d(g_sample_index, g_pixel_seed, 0u));
  }
  g_incomplete = false;
  g_primary_escaped = false;
  vec2 jitter = sample_2d(0u);
  vec2 film = (vec2(float(pixel.x), float(pixel.y)) + jitter) / vec2(u_resolution);
  vec2 lens = sample_2d(1u);
  return start_path(camera_ray(cam, film, lens));
}

// Adds u_samples_per_pass samples to the pixel's running mean and variance: `accumulation`
// (rgb the mean, a the discarded count), `compensation` (what float32 could not hold of the
// mean; a the samples taken), `variance` and `variance_compensation` (the same for the mean
// squared deviation) hold the pixel's state before the pass (zero before the first) and
// receive it after; `covered` counts the finite samples whose camera ray hit a surface. The
// two entry points (trace.frag, trace.comp) differ only in where they read and write it. A
// pixel outside the region, or waiting with adaptive sampling, keeps its state.
bool in_sample_region(ivec2 pixel) {
  return !u_region_on || (all(greaterThanEqual(pixel, u_region.xy)) && all(lessThan(pixel, u_region.zw)));
}

void add_samples(ivec2 pixel, inout vec4 accumulation, inout vec4 compensation,
                 inout vec3 variance, inout vec3 variance_compensation, inout float covered) {
  if (u_read_every_sampler) accumulation += every_sampler();
  if (!in_sample_region(pixel)) return;
  if (!adaptive_pixel_active(accumulation, compensation, variance)) return;
  CameraFrame cam = CameraFrame(u_cam_origin, u_cam_right, u_cam_up, u_cam_forward,
                                u_cam_tan_half_vfov, u_cam_aspect, u_cam_aperture, u_cam_focus);
  uint row = uint(pixel.y);
  vec4 previous = accumulation;
  // Without adaptive sampling every pixel has taken u_samples_before samples; with it, its own
  // count, so that its sample indices (and its Sobol' points) continue without a gap.
  uint samples_before = u_adaptive || u_per_pixel_counts ? uint(compensation.a) : u_samples_before;
  // The pass adds the sum of the samples' deviations from the previous mean, not their sum:
  // mean += sum(l - mean) / n. The deviations are small (exactly 0 for a constant once the mean
  // has reached it), so their rounding is small too; summing the samples themselves and
  // subtracting k * mean rounds both terms at the size of k * mean, and that error, divided by
  // n each pass, drifted a constant by 1e-5 (relative) over 1000 passes of 1000 samples
  // (hard_Accumulation.MillionSamplesOfAConstantDoNotDrift).
  g_pixel_seed = sobol_pixel_seed(uint(pixel.x), row, u_seed);
  vec3 deviation_sum = vec3(0.0);
  // The variance's sums are taken about `shift`: the previous mean, or for a pixel's first
  // finite sample that sample itself (about 0, sum(l^2) - sum(l)^2 / k would cancel to a
  // rounding error of the size of l^2 for a constant l).
  bool no_mean_yet = float(samples_before) - previous.a <= 0.0;
  vec3 shift = previous.rgb;
  vec3 shifted_sum = vec3(0.0);
  vec3 shifted_square_sum = vec3(0.0);
  int finite_count = 0;
  int covered_count = 0;
  // Path regeneration: one loop over the pass's bounces, in which a lane whose path has ended
  // starts its next sample. A SIMD group (8 lanes on llvmpipe) runs each iteration while any
  // lane is active, so with a loop per sample every sample would cost the longest path of the
  // group. Starting at once keeps lanes busy where paths differ much in length (closed rooms);
  // where they are short and alike (open scenes) starting together pays the start-up code once
  // per group and keeps the group's rays coherent (u_restart_together; bench/reports/THROUGHPUT.md).
  // Each sample is the same (its random numbers, its arithmetic) as when traced alone, and the
  // samples are added in order, so the image does not depend on the policy.
  // The loop's own condition ends it, not a `break` alone: Mesa 25's llvmpipe never ended a
  // `for (;;)` left only by a `break` in this fragment shader (the same loop in the compute
  // shader ended).
  int s = 0;
  PathState path = start_sample(cam, pixel, samples_before);
  bool in_flight = true;
  while (s < u_samples_per_pass) {
    if (in_flight) in_flight = continue_path(path);
    // Every lane still in the loop votes, so that the vote sees the whole active group.
#if defined(GLINT_GROUP_VOTE)
    bool group_idle = allInvocationsARB(!in_flight);
#else
    bool group_idle = true;
#endif
    if (in_flight || (u_restart_together && !group_idle)) continue;
    vec3 l = path.radiance;
    // The firefly clamp scales a sample down to luminance u_clamp: biased, off by default.
    float lum = luminance(l);
    if (u_clamp > 0.0 && lum > u_clamp) l *= u_clamp / lum;
    if (is_finite(l) && !g_incomplete) {
      deviation_sum += l - previous.rgb;
      if (no_mean_yet && finite_count == 0) shift = l;
      shifted_sum += l - shift;
      shifted_square_sum += (l - shift) * (l - shift);
      ++finite_count;
      if (!g_primary_escaped) ++covered_count;
    }
    if (++s < u_samples_per_pass) {
      path = start_sample(cam, pixel, samples_before + uint(s));
      in_flight = true;
    }
  }
  float discarded = previous.a + float(u_samples_per_pass - finite_count);
  float taken = float(samples_before) + float(u_samples_per_pass);
  float finite_total = taken - discarded;
  // The increment sum(l - mean) / n itself is rounded when added to the mean: by up to half an
  // ulp of the mean, and when most increments are smaller than that (a pixel of a constant
  // background with a rare brighter sample, late in a long run) they round the same way every
  // time. Plain float32 then drifted such a pixel by 0.1% over 10^5 one-sample passes
  // (tests/soak, bench/reports/SOAK.md). Kahan's compensated summation (Higham, "Accuracy and
  // Stability of Numerical Algorithms", 2nd ed., §4.3) keeps what each addition lost in
  // `compensation` and adds it back the next time: the represented mean is mean - compensation
  // (so the deviations, taken from `mean`, are short by finite_count * compensation).
  // `precise` forbids the compiler to simplify (t - mean) - y to 0.
  precise vec3 mean = previous.rgb;
  precise vec3 lost = compensation.rgb;
  if (finite_total > 0.0) {
    precise vec3 y = (deviation_sum + float(finite_count) * lost) / finite_total - lost;
    precise vec3 t = mean + y;
    lost = (t - mean) - y;
    mean = t;
  }
  // The variance, v = M2 / n, by Chan, Golub and LeVeque's pairwise update ("Algorithms for
  // computing the sample variance", 1983) of M2 with the pass's k samples, written with the
  // deviations d from the previous mean (from the first sample when there is none):
  // M2' = M2 + sum(d^2) - sum(d)^2 / n', so that v' = v + (sum(d^2) - sum(d)^2 / n' - k v) / n'.
  // Every term is a deviation, not a square of the radiance, so nothing cancels; the
  // increment is added with Kahan's compensation as the mean's is.
  precise vec3 v = variance;
  precise vec3 v_lost = variance_compensation;
  if (finite_total > 0.0) {
    vec3 m2_increment = max(shifted_square_sum - shifted_sum * shifted_sum / finite_total, vec3(0.0));
    precise vec3 y = (m2_increment - float(finite_count) * (v - v_lost)) / finite_total - v_lost;
    precise vec3 t = v + y;
    v_lost = (t - v) - y;
    v = t;
  }
  accumulation = vec4(mean, discarded);
  compensation = vec4(lost, taken);
  variance = v;
  variance_compensation = v_lost;
  covered += float(covered_count);
}
