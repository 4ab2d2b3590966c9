// Importance-sampling tables for a lat-long environment image (docs/DESIGN.md §6): a piecewise-
// constant 2-D distribution over the texels, sampled and evaluated on the GPU and in the tests
// by shaders/lib/environment_sampling.glsl (one copy of the maths).
#pragma once

#include <vector>

#include "renderer/image.h"

namespace glint {

// The sampling weight of every texel, row-major (row 0 = the top, v = 0), in double:
// luminance(mean of the bilinearly filtered image over the texel) x sin(theta at the row's
// centre). The GPU lookup is bilinear (repeat in u, clamp to edge in v), so a texel's area sees
// its own value and its eight neighbours'; the mean over the texel is the separable filter
// [1/8, 3/4, 1/8] in x and y. That weight is > 0 exactly where the filtered lookup can be > 0
// somewhere in the texel (no directions with radiance and pdf 0), and follows a sun's bilinear
// footprint instead of spreading it evenly over 3x3 texels as a neighbourhood maximum would.
// Non-finite texels and negative channels count as 0. An image with no positive weight (all
// black) gets luminance 1 everywhere: the distribution of uniform directions, row by row.
std::vector<double> environment_texel_weights(const Image& image);

// Row CDFs and a marginal CDF over the rows, accumulated in double and stored as float: each
// starts at exactly 0, ends at exactly 1 and is monotone (rounding a monotone sequence is
// monotone). A row whose weights are all 0 gets a uniform CDF (it is never chosen: its
// marginal interval is empty). No float prefix sum runs over more than one row of texels.
struct EnvironmentDistribution {
  int width = 0;
  int height = 0;
  std::vector<float> marginal_cdf;     // height + 1 entries
  std::vector<float> conditional_cdf;  // height rows of width + 1 entries

  float conditional(int row, int i) const {
    return conditional_cdf[static_cast<size_t>(row) * (width + 1) + i];
  }
  // The probability of texel (x, y) as the sampler realises it (CDF differences), in double.
  double texel_probability(int x, int y) const;
};

// The share of the map's power (its sampling probability) in its brightest texels (by
// radiance, probability over solid angle) that together cover `solid_angle_share` of the
// sphere: about solid_angle_share for a uniform sky, near 1 for a sun. Manifold next-event
// estimation samples the environment where this is high (renderer/mnee_casters.h).
double environment_peak_share(const EnvironmentDistribution& d, double solid_angle_share);

// weights: width x height, row-major, >= 0 and finite (as environment_texel_weights returns).
EnvironmentDistribution build_environment_distribution(int width, int height,
                                                       const std::vector<double>& weights);
// From an image; an empty image gives a 1x1 uniform distribution.
EnvironmentDistribution build_environment_distribution(const Image& image);

// The tables as one float array (float stride 4, no padding; the shader reads it from an R32I
// texture, each texel the float's bits):
//   data[i]                                  marginal CDF, i in [0, height]
//   data[(height + 1) + row * (width + 1) + i]  conditional CDF of row, i in [0, width]
// width and height go in a uniform. trace_common.glsl then defines, before including
// lib/environment_sampling.glsl:
//   layout(binding = N) uniform isamplerBuffer u_env_cdf_table;
//   uniform ivec2 u_env_distribution_size;
//   ivec2 env_distribution_size() { return u_env_distribution_size; }
//   float env_marginal_cdf(int i) { return env_cdf(i); }  // env_cdf: the texel's float
//   float env_conditional_cdf(int row, int i) {
//     return env_cdf(u_env_distribution_size.y + 1 + row * (u_env_distribution_size.x + 1) + i);
//   }
struct PackedEnvironmentDistribution {
  int width = 0;
  int height = 0;
  std::vector<float> data;
};
PackedEnvironmentDistribution pack_environment_distribution(const EnvironmentDistribution& d);

}  // namespace glint
