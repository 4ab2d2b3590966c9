#version 450 core
// (renderer/shader_features.cpp inserts `#define GLINT_NO_...` lines here for what the scene
// lacks; none defined is the generic program.)
// Path tracing pass: adds u_samples_per_pass samples to every pixel's running mean.
// Accumulation texel: rgb = mean of the finite samples so far, a = count of non-finite
// samples discarded. The pass reads the previous accumulation and writes the next one
// (ping-pong); the exact sample count lives on the CPU.
#include "lib/common.glsl"
#include "lib/rng.glsl"
#include "lib/mapping.glsl"
#include "lib/sampling.glsl"
#include "lib/intersect.glsl"
#include "lib/camera.glsl"
#include "lib/bsdf.glsl"

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
  ivec4 layers;   // texture-array layers of colour, emission, roughness; -1 for none
};

layout(std430, binding = 0) readonly buffer Spheres { GpuSphere spheres[]; };
layout(std430, binding = 1) readonly buffer Quads { GpuQuad quads[]; };
layout(std430, binding = 2) readonly buffer Materials { GpuMaterial materials[]; };
layout(std430, binding = 3) readonly buffer LayerSizes { ivec4 layer_sizes[]; };

layout(binding = 0) uniform sampler2D u_previous;
layout(binding = 1) uniform sampler2DArray u_textures;
layout(binding = 2) uniform sampler2D u_environment;

uniform ivec2 u_resolution;
uniform uint u_samples_before;  // samples already in the accumulation
uniform int u_samples_per_pass;
uniform uint u_seed;
uniform int u_max_bounces;
uniform int u_sphere_count;
uniform int u_quad_count;
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

layout(location = 0) out vec4 out_accumulation;

uint g_rng;
float rand() {
  g_rng = rng_advance(g_rng);
  return rng_to_unit_float(g_rng);
}

vec4 texture_lookup(int layer, vec2 uv) {
#if defined(GLINT_NO_TEXTURES)
  return vec4(1.0);  // no used material has a texture: every layer is -1
#else
  if (layer < 0) return vec4(1.0);
  BilinearTaps taps = bilinear_taps(uv, layer_sizes[layer].xy);
  vec4 a = texelFetch(u_textures, ivec3(taps.texels.x, taps.texels.y, layer), 0);
  vec4 b = texelFetch(u_textures, ivec3(taps.texels.z, taps.texels.y, layer), 0);
  vec4 c = texelFetch(u_textures, ivec3(taps.texels.x, taps.texels.w, layer), 0);
  vec4 d = texelFetch(u_textures, ivec3(taps.texels.z, taps.texels.w, layer), 0);
  return mix(mix(a, b, taps.weight.x), mix(c, d, taps.weight.x), taps.weight.y);
#endif
}

vec3 environment(vec3 d) {
#if !defined(GLINT_NO_ENV_TEXTURE)
  if (u_env_textured) return u_env_color * texture(u_environment, environment_uv(d, u_env_rotation)).rgb;
#endif
  return u_env_color;
}

struct SceneHit {
  float t;
  vec3 position;  // on the surface to a few ulps of error_scale (not o + t d)
  float error_scale;  // coordinate magnitude of the shape (see surface_offset_distance)
  vec3 normal;  // geometric, unit, not yet flipped
  vec2 uv;
  int material;
};

SceneHit intersect_scene(Ray ray) {
  SceneHit hit = SceneHit(1e30, vec3(0.0), 0.0, vec3(0.0), vec2(0.0), -1);
  int sphere_index = -1;
  for (int i = 0; i < u_sphere_count; ++i) {
    vec4 s = spheres[i].center_radius;
    float t = intersect_sphere(ray, s.xyz, s.w, 0.0, hit.t);
    if (t != NO_HIT) {
      hit.t = t;
      sphere_index = i;
    }
  }
  int quad_index = -1;
  for (int i = 0; i < u_quad_count; ++i) {
    GpuQuad q = quads[i];
    QuadHit h = intersect_quad(ray, q.p0.xyz, q.p1.xyz, q.p2.xyz, q.p3.xyz, q.uv01.xy, q.uv01.zw,
                               q.uv23.xy, q.uv23.zw, 0.0, hit.t);
    if (h.t != NO_HIT) {
      hit.t = h.t;
      hit.uv = h.uv;
      hit.position = h.position;
      quad_index = i;
    }
  }
  if (quad_index >= 0) {
    GpuQuad q = quads[quad_index];
    hit.normal = q.normal.xyz;
    hit.error_scale = quad_error_scale(q.p0.xyz, q.p1.xyz, q.p2.xyz, q.p3.xyz);
    hit.material = q.material.x;
  } else if (sphere_index >= 0) {
    vec4 s = spheres[sphere_index].center_radius;
    hit.position = sphere_hit_point(ray, hit.t, s.xyz, s.w);
    hit.error_scale = sphere_error_scale(s.xyz, s.w);
    hit.normal = normalize(hit.position - s.xyz);
    hit.uv = direction_to_uv(hit.normal);
    hit.material = spheres[sphere_index].material.x;
  }
  return hit;
}

// Coverage pass-throughs allowed per path: a stack of cut-out surfaces deeper than this
// is treated as opaque at the last one.
const int MAX_PASS_THROUGH = 64;

vec3 trace_path(Ray ray) {
  vec3 radiance = vec3(0.0);
  vec3 throughput = vec3(1.0);
  int bounces = 0;
  int passes = 0;
  for (;;) {
    SceneHit hit = intersect_scene(ray);
    if (hit.material < 0) {
      radiance += throughput * environment(ray.direction);
      break;
    }
    GpuMaterial gm = materials[hit.material];
    vec3 p = hit.position;
    vec3 wo = -ray.direction;
    vec3 n = dot(hit.normal, wo) >= 0.0 ? hit.normal : -hit.normal;
    vec4 color_tex = texture_lookup(gm.layers.x, hit.uv);
#if !defined(GLINT_NO_COVERAGE)  // without it coverage is 1: no test, and no rand() either
    float coverage = gm.params.z * color_tex.a;
    if (coverage < 1.0 && passes < MAX_PASS_THROUGH && rand() >= coverage) {
      // Not a bounce: the ray continues unchanged past the surface.
      ray.origin = offset_surface_point(p, -n, hit.error_scale);
      ++passes;
      continue;
    }
#endif
#if !defined(GLINT_NO_EMITTERS)
    radiance += throughput * gm.emission.rgb * texture_lookup(gm.layers.y, hit.uv).rgb;
#endif
    if (bounces >= u_max_bounces) break;
    SurfaceMaterial m = SurfaceMaterial(int(gm.color.a), gm.color.rgb * color_tex.rgb,
                                        gm.params.x * texture_lookup(gm.layers.z, hit.uv).r,
                                        gm.params.y);
    float u_lobe = rand();
    vec2 u = vec2(rand(), rand());
    BsdfSample s = sample_bsdf(m, n, wo, u_lobe, u);
    if (!s.valid) break;
    throughput *= s.weight;
    if (max_component(throughput) <= 0.0) break;
    ray = Ray(offset_surface_point(p, dot(s.wi, n) > 0.0 ? n : -n, hit.error_scale), s.wi);
    ++bounces;
  }
  return radiance;
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  CameraFrame cam = CameraFrame(u_cam_origin, u_cam_right, u_cam_up, u_cam_forward,
                                u_cam_tan_half_vfov, u_cam_aspect, u_cam_aperture, u_cam_focus);
  // Texel row y holds image row y (top first), so read-back needs no flip.
  uint row = uint(pixel.y);
  vec4 previous = u_samples_before > 0u ? texelFetch(u_previous, pixel, 0) : vec4(0.0);
  // The pass adds the sum of the samples' deviations from the previous mean, not their sum:
  // mean += sum(l - mean) / n. The deviations are small (exactly 0 for a constant once the mean
  // has reached it), so their rounding is small too; summing the samples themselves and
  // subtracting k * mean rounds both terms at the size of k * mean, and that error, divided by
  // n each pass, drifted a constant by 1e-5 (relative) over 1000 passes of 1000 samples
  // (hard_Accumulation.MillionSamplesOfAConstantDoNotDrift).
  vec3 deviation_sum = vec3(0.0);
  int finite_count = 0;
  for (int s = 0; s < u_samples_per_pass; ++s) {
    g_rng = rng_seed(uint(pixel.x), row, u_samples_before + uint(s), u_seed);
    vec2 jitter = vec2(rand(), rand());
    vec2 film = (vec2(float(pixel.x), float(row)) + jitter) / vec2(u_resolution);
    vec2 lens = vec2(rand(), rand());
    vec3 l = trace_path(camera_ray(cam, film, lens));
    if (is_finite(l)) {
      deviation_sum += l - previous.rgb;
      ++finite_count;
    }
  }
  float discarded = previous.a + float(u_samples_per_pass - finite_count);
  float finite_total = float(u_samples_before) + float(u_samples_per_pass) - discarded;
  vec3 mean = previous.rgb;
  if (finite_total > 0.0) mean += deviation_sum / finite_total;
  out_accumulation = vec4(mean, discarded);
}
