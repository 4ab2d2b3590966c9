#version 450 core
// The auxiliary images that guide the denoiser (renderer/aov_pass.h, docs/DESIGN.md,
// Denoising): per sample, the albedo and the normal at the first surface that is not a perfect
// specular one, following ideal mirrors by reflection and smooth thin glass straight through,
// as Open Image Denoise's documentation asks of specular surfaces. Each delta surface passed
// multiplies the albedo by its weight (a mirror's Fresnel colour, the glass's tint). A path that
// escapes gives that weight as albedo (1 for the background itself) and a zero normal.
// The camera ray is drawn exactly as add_samples draws it (same pixel jitter and lens point),
// so the images line up with the colour sample by sample. Additive blending sums the samples:
// rgb the sum, a the count.
#include "trace_common.glsl"

layout(location = 0) out vec4 out_albedo;
layout(location = 1) out vec4 out_normal;

// Delta surfaces followed before giving up (then the last one counts as the surface).
const int MAX_SPECULAR_CHAIN = 16;

void first_diffuse_surface(Ray ray, out vec3 albedo, out vec3 normal) {
  vec3 weight = vec3(1.0);
  int passes = 0;
  for (int chain = 0;;) {
    SceneHit hit = intersect_scene(ray);
    if (hit.material < 0) {
      albedo = weight;
      normal = vec3(0.0);
      return;
    }
    GpuMaterial gm = material_at(hit.material);
    vec3 wo = -ray.direction;
    vec3 n = dot(hit.normal, wo) >= 0.0 ? hit.normal : -hit.normal;
    vec4 color_tex = texture_lookup(gm.layers.x, hit.uv);
    float coverage = gm.params.z * color_tex.a;
    if (coverage < 1.0 && passes < MAX_PASS_THROUGH && rand() >= coverage) {
      ray.origin = offset_surface_point(hit.position, -n, hit.error_scale);
      ++passes;
      continue;
    }
    SurfaceMaterial m = surface_material(gm, color_tex, hit.uv);
    if (!is_delta_material(m) || chain >= MAX_SPECULAR_CHAIN) {
      albedo = weight * m.color;
      normal = n;
      return;
    }
    ++chain;
    if (m.type == MATERIAL_TRANSPARENT) {
      weight *= m.color;
      ray.origin = offset_surface_point(hit.position, -n, hit.error_scale);
    } else {
      weight *= fresnel_schlick(m.color, dot(n, wo));
      ray = Ray(offset_surface_point(hit.position, n, hit.error_scale), reflect(ray.direction, n));
    }
  }
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  CameraFrame cam = CameraFrame(u_cam_origin, u_cam_right, u_cam_up, u_cam_forward,
                                u_cam_tan_half_vfov, u_cam_aspect, u_cam_aperture, u_cam_focus);
  uint row = uint(pixel.y);
  g_pixel_seed = sobol_pixel_seed(uint(pixel.x), row, u_seed);
  vec3 albedo_sum = vec3(0.0);
  vec3 normal_sum = vec3(0.0);
  float count = 0.0;
  if (u_read_every_sampler) albedo_sum += every_sampler().rgb;
  for (int s = 0; s < u_samples_per_pass; ++s) {
    g_rng = rng_seed(uint(pixel.x), row, u_samples_before + uint(s), u_seed);
    g_sample_index = u_samples_before + uint(s);
    if (u_sobol) g_primary = sobol_sample_4d(g_sample_index, g_pixel_seed, 0u);
    g_incomplete = false;
    vec2 jitter = sample_2d(0u);
    vec2 film = (vec2(float(pixel.x), float(row)) + jitter) / vec2(u_resolution);
    vec2 lens = sample_2d(1u);
    vec3 albedo, normal;
    first_diffuse_surface(camera_ray(cam, film, lens), albedo, normal);
    if (g_incomplete || !is_finite(albedo) || !is_finite(normal)) continue;
    albedo_sum += albedo;
    normal_sum += normal;
    count += 1.0;
  }
  out_albedo = vec4(albedo_sum, count);
  out_normal = vec4(normal_sum, count);
}
