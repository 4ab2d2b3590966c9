// The random numbers of a camera sample: the PCG stream and the Sobol dimensions by purpose.
// GLSL only, part of the trace program (shaders/trace_common.glsl includes it after the
// shared maths); not compiled as C++ (renderer/shader_lib.h), since it reads the uniforms,
// tables and samplers of the trace program.

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
#if defined(GLINT_MNEE)
// Manifold next-event estimation at bounce b (lib/manifold_nee.glsl): 1-D dimension d picks the
// light, 2-D dimension d the point on it, 1-D dimension d + 1 the caster; in a range of their
// own (padded dimensions are hashed, any index is as good), so that adding MNEE leaves the
// other decisions' dimensions where they were.
const uint MNEE_DIMENSION_BASE = 0x10000u;
uint mnee_dimension(int bounce) { return MNEE_DIMENSION_BASE + 2u * uint(bounce); }
#endif
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
