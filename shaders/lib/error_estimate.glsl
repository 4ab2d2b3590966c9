// A pixel's estimated relMSE without a reference (docs/DESIGN.md §4.1), the definition of
// renderer/image_metrics.h with its epsilon 0.01: the variance of the pixel's mean,
// M2 / (n (n - 1)) = variance / (n - 1) for the mean squared deviation `variance` of n finite
// samples, over mean^2 + 0.01, averaged over the three channels. With fewer than two finite
// samples there is no estimate: -1.
#ifndef GLINT_ERROR_ESTIMATE_GLSL
#define GLINT_ERROR_ESTIMATE_GLSL

float estimated_pixel_relmse(vec3 mean, vec3 variance, float finite) {
  if (finite < 2.0f) return -1.0f;
  vec3 r = max(variance, vec3(0.0f)) / (finite - 1.0f) / (mean * mean + vec3(0.01f));
  return (r.x + r.y + r.z) / 3.0f;
}

#endif
