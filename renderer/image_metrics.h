// Error of a rendered image against a reference (convergence logging). Both images are
// linear RGB radiance of the same size; alpha is ignored except by nonfinite_count, where it is
// the accumulation's count of discarded samples (GpuRenderer::read_accumulation).
#pragma once

#include <cstddef>
#include <stdexcept>

#include "renderer/image.h"

namespace glint {

// The relative errors use this epsilon so that black reference pixels do not divide by zero
// (the usual value for relMSE in the rendering literature; docs/DESIGN.md §10).
inline constexpr double kMetricEpsilon = 0.01;
// Fraction of pixels, the largest per-pixel relMSE values, dropped by relmse_trimmed.
inline constexpr double kTrimFraction = 0.001;

struct ImageMetrics {
  // Mean over pixels and RGB channels of (x - r)^2 / (r^2 + 0.01).
  double relmse = 0;
  // Per-pixel relMSE (the mean of the above over the three channels), with the largest
  // floor(0.1% of the pixel count) of them dropped, averaged over the pixels that remain.
  // A single firefly can dominate relmse; this shows the error without the worst few pixels.
  double relmse_trimmed = 0;
  // Mean over pixels and RGB channels of |x - r| / (|r| + 0.01).
  double mape = 0;
  // (mean lum(x) - mean lum(r)) / mean lum(r), Rec. 709 luminance; NaN when the reference's
  // mean luminance is 0 (a relative bias of a black image is undefined).
  double mean_bias = 0;
};

// Thrown when the two images cannot be compared (different sizes, empty, short pixel arrays).
struct ImageMetricsError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

ImageMetrics compare_images(const Image& image, const Image& reference);

// Sum of the alpha channel: for an accumulation image, the count of non-finite samples that
// the trace pass discarded.
double nonfinite_count(const Image& accumulation);

// Rec. 709 / sRGB-primaries luminance of linear RGB.
inline double luminance(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }

}  // namespace glint
