// Random numbers: the PCG hash of Jarzynski and Olano, "Hash Functions for GPU Rendering"
// (JCGT 2020), used both to seed a per-pixel, per-sample stream and to advance it.
#ifndef GLINT_RNG_GLSL
#define GLINT_RNG_GLSL

uint pcg_hash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// The stream of one sample of one pixel: independent for every (pixel, sample, seed).
uint rng_seed(uint pixel_x, uint pixel_y, uint sample_index, uint seed) {
  return pcg_hash(pixel_x + pcg_hash(pixel_y + pcg_hash(sample_index + pcg_hash(seed))));
}

uint rng_advance(uint state) { return pcg_hash(state); }

// The top 24 bits as a float in [0, 1): exact, and never 1.
float rng_to_unit_float(uint state) { return float(state >> 8u) * (1.0f / 16777216.0f); }

#endif
