// A hit's material as the BSDF reads it, its emission, and what passes straight through it
// (shadow rays), with the pass-through and roulette constants of a path.
// GLSL only, part of the trace program (shaders/trace_common.glsl includes it after the
// shared maths); not compiled as C++ (renderer/shader_lib.h), since it reads the uniforms,
// tables and samplers of the trace program.

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
