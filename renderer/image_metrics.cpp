#include "renderer/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace glint {
namespace {

std::string size_text(const Image& img) {
  return std::to_string(img.width) + "x" + std::to_string(img.height);
}

void check_image(const Image& img, const char* which) {
  if (img.width <= 0 || img.height <= 0)
    throw ImageMetricsError(std::string("the ") + which + " image is empty (" + size_text(img) + ")");
  if (img.pixels.size() != static_cast<size_t>(img.width) * img.height * 4)
    throw ImageMetricsError(std::string("the ") + which + " image has " +
                            std::to_string(img.pixels.size()) + " floats, not " + size_text(img) + " RGBA");
}

}  // namespace

ImageMetrics compare_images(const Image& image, const Image& reference) {
  check_image(image, "rendered");
  check_image(reference, "reference");
  if (image.width != reference.width || image.height != reference.height)
    throw ImageMetricsError("the image is " + size_text(image) + " but the reference is " +
                            size_text(reference));

  const size_t n = static_cast<size_t>(image.width) * image.height;
  std::vector<double> per_pixel(n);
  // Sums in double: a 4K image has ~2.5e7 terms, too many for float accumulation.
  double sum_rel = 0, sum_ape = 0, lum_x = 0, lum_r = 0;
  for (size_t i = 0; i < n; ++i) {
    const float* x = &image.pixels[i * 4];
    const float* r = &reference.pixels[i * 4];
    double pixel_rel = 0;
    for (int c = 0; c < 3; ++c) {
      double d = double(x[c]) - double(r[c]);
      pixel_rel += d * d / (double(r[c]) * r[c] + kMetricEpsilon);
      sum_ape += std::abs(d) / (std::abs(double(r[c])) + kMetricEpsilon);
    }
    per_pixel[i] = pixel_rel / 3.0;
    sum_rel += pixel_rel;
    lum_x += luminance(x[0], x[1], x[2]);
    lum_r += luminance(r[0], r[1], r[2]);
  }

  ImageMetrics m;
  m.relmse = sum_rel / (3.0 * n);
  m.mape = sum_ape / (3.0 * n);
  m.mean_bias = lum_r != 0 ? (lum_x - lum_r) / lum_r : std::numeric_limits<double>::quiet_NaN();

  // Keep the n - floor(0.001 n) smallest per-pixel values (partial sort, no full sort needed).
  // NaN compares false with everything, so treat it as the largest value (it is trimmed first).
  const size_t drop = static_cast<size_t>(std::floor(kTrimFraction * double(n)));
  const size_t keep = n - drop;
  auto less = [](double a, double b) { return std::isnan(b) ? !std::isnan(a) : a < b; };
  if (drop > 0) std::nth_element(per_pixel.begin(), per_pixel.begin() + keep, per_pixel.end(), less);
  double kept = 0;
  for (size_t i = 0; i < keep; ++i) kept += per_pixel[i];
  m.relmse_trimmed = kept / double(keep);
  return m;
}

double nonfinite_count(const Image& accumulation) {
  double sum = 0;
  for (size_t i = 3; i < accumulation.pixels.size(); i += 4) sum += accumulation.pixels[i];
  return sum;
}

}  // namespace glint
