// Owen-scrambled Sobol points with hash-based scrambling and Burley's padding (Burley 2020,
// "Practical Hash-based Owen Scrambling", JCGT 9(4)): every dimension pair is the first two
// Sobol dimensions, and every 4-D group the first four, with its own shuffle of the sample index
// and its own scramble of each coordinate. Needs rng.glsl (pcg_hash, rng_to_unit_float).
#ifndef GLINT_SOBOL_GLSL
#define GLINT_SOBOL_GLSL

// Sobol dimension 0 as 32-bit fixed point: direction numbers v_k = 2^(31-k), i.e. the
// van der Corput radical inverse (the bit reversal of the index).
uint sobol_dimension0(uint index) { return bitfieldReverse(index); }

// Sobol dimension 1: primitive polynomial x + 1 (degree s = 1, m_1 = 1). The recurrence of
// Bratley and Fox, m_k = 2 m_(k-1) xor m_(k-1), with v_k = m_k / 2^k in 32-bit fixed point
// (V_k = m_k << (32 - k)), is V_k = V_(k-1) xor (V_(k-1) >> 1), starting from V_1 = 2^31. Its
// generator matrix is Pascal's triangle mod 2: bit 31 - r of V_(j+1) is C(j, r) mod 2, which
// by Lucas's theorem is 1 exactly when the bits of r are a subset of those of j. So bit 31 - r
// of the point is the xor of the index bits j that contain r: the superset xor transform of
// the index, five shift-and-xor steps (one per bit of the bit position), bit-reversed. No
// loop: a loop over the index bits ran 32 times for a scrambled index, in every lane.
uint sobol_dimension1(uint index) {
  uint y = index;
  y ^= (y >> 1u) & 0x55555555u;
  y ^= (y >> 2u) & 0x33333333u;
  y ^= (y >> 4u) & 0x0f0f0f0fu;
  y ^= (y >> 8u) & 0x00ff00ffu;
  y ^= (y >> 16u) & 0x0000ffffu;
  return bitfieldReverse(y);
}

// Sobol dimensions 2 and 3 with the direction numbers of Joe and Kuo ("Constructing Sobol
// sequences with better two-dimensional projections", SIAM J. Sci. Comput. 30, 2008; the
// new-joe-kuo-6.21201 table): dimension 2 has polynomial x^2 + x + 1 (s = 2, a = 1,
// m = 1, 3), dimension 3 has x^3 + x + 1 (s = 3, a = 1, m = 1, 3, 1). Bratley and Fox's
// recurrence m_k = 2 a_1 m_(k-1) xor ... xor 2^s m_(k-s) xor m_(k-s) in 32-bit fixed point
// (V_k = m_k << (32 - k)) is V_k = V_(k-1) xor V_(k-2) xor (V_(k-2) >> 2) for dimension 2 and
// V_k = V_(k-2) xor V_(k-3) xor (V_(k-3) >> 3) for dimension 3. The loops have a constant
// count and no branch (V_k masked by index bit k - 1), so that the compiler unrolls them and
// folds the direction numbers into constants.
uint sobol_dimension2(uint index) {
  uint result = 0u;
  uint a = 0x80000000u, b = 0xc0000000u;  // V_k and V_(k+1), from k = 1
  for (int bit = 0; bit < 32; ++bit) {
    result ^= a & (0u - ((index >> uint(bit)) & 1u));
    uint next = b ^ a ^ (a >> 2u);
    a = b;
    b = next;
  }
  return result;
}
uint sobol_dimension3(uint index) {
  uint result = 0u;
  uint a = 0x80000000u, b = 0xc0000000u, c = 0x20000000u;  // V_k, V_(k+1), V_(k+2)
  for (int bit = 0; bit < 32; ++bit) {
    result ^= a & (0u - ((index >> uint(bit)) & 1u));
    uint next = b ^ a ^ (a >> 3u);
    a = b;
    b = c;
    c = next;
  }
  return result;
}

// A bijection of 32-bit values in which bit i of the result depends only on bits 0..i of the
// input (adding, and xor with a multiple by an even constant, carry only upwards): applied to
// the bit-reversed value it flips every binary digit depending only on the more significant
// ones, which is an Owen scramble (Burley 2020, sec. 3, with the Laine-Karras style hash and
// the constants given there).
uint laine_karras_permutation(uint x, uint seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// Owen scramble of a 32-bit fixed-point value in [0,1), the tree of random flips given by seed.
uint nested_uniform_scramble(uint x, uint seed) {
  return bitfieldReverse(laine_karras_permutation(bitfieldReverse(x), seed));
}

// The pixel's scrambling seed, from the pixel and the project's seed (rng_seed's chain, with
// a domain constant so that it is not the seed of any PCG sample stream).
uint sobol_pixel_seed(uint pixel_x, uint pixel_y, uint seed) {
  return pcg_hash(pixel_x + pcg_hash(pixel_y + pcg_hash(seed ^ 0x5eed50b1u)));
}

// Seeds of one dimension (pair): independent for every (pixel seed, dimension, kind).
uint sobol_dimension_seed(uint pixel_seed, uint dimension, uint kind) {
  return pcg_hash(pixel_seed + pcg_hash(dimension + pcg_hash(kind)));
}

// Point sample_index of dimension pair dimension_pair (dimensions 2 d and 2 d + 1) in [0,1)^2.
// The index is Owen-scrambled first (a shuffle): the first 2^k indices of a pixel map to one
// aligned block of 2^k Sobol indices, which is a (0,k,2)-net, so every power-of-two prefix of
// a progressive render stays stratified; a different shuffle per pair decorrelates the pairs.
vec2 sobol_sample_2d(uint sample_index, uint pixel_seed, uint dimension_pair) {
  uint seed = sobol_dimension_seed(pixel_seed, dimension_pair, 2u);
  uint index = nested_uniform_scramble(sample_index, seed);
  uint x = nested_uniform_scramble(sobol_dimension0(index), pcg_hash(seed));
  uint y = nested_uniform_scramble(sobol_dimension1(index), pcg_hash(seed + 1u));
  return vec2(rng_to_unit_float(x), rng_to_unit_float(y));
}

// Point sample_index of the 4-D group `group` (Sobol dimensions 0 to 3 under one shuffle, each
// coordinate scrambled on its own, as Burley 2020 does for 4-D points): for decisions that
// interact, so that the 4-D point set, not only its 2-D halves, is stratified. Seeded apart
// from the pairs.
vec4 sobol_sample_4d(uint sample_index, uint pixel_seed, uint group) {
  uint seed = sobol_dimension_seed(pixel_seed, group, 4u);
  uint index = nested_uniform_scramble(sample_index, seed);
  uint x = nested_uniform_scramble(sobol_dimension0(index), pcg_hash(seed));
  uint y = nested_uniform_scramble(sobol_dimension1(index), pcg_hash(seed + 1u));
  uint z = nested_uniform_scramble(sobol_dimension2(index), pcg_hash(seed + 2u));
  uint w = nested_uniform_scramble(sobol_dimension3(index), pcg_hash(seed + 3u));
  return vec4(rng_to_unit_float(x), rng_to_unit_float(y), rng_to_unit_float(z), rng_to_unit_float(w));
}

// One dimension in [0,1): a shuffled, scrambled van der Corput sequence, seeded apart from the
// pairs (a 1-D dimension d and the pair d are independent).
float sobol_sample_1d(uint sample_index, uint pixel_seed, uint dimension) {
  uint seed = sobol_dimension_seed(pixel_seed, dimension, 1u);
  uint index = nested_uniform_scramble(sample_index, seed);
  return rng_to_unit_float(nested_uniform_scramble(sobol_dimension0(index), pcg_hash(seed)));
}

#endif
