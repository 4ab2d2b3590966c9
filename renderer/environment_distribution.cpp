#include "renderer/environment_distribution.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace glint {

namespace {

double texel_luminance(const float* px) {
  double sum = 0;
  const double coeff[3] = {0.2126, 0.7152, 0.0722};  // as luminance() in shaders/lib/common.glsl
  for (int c = 0; c < 3; ++c) {
    double v = px[c];
    if (!std::isfinite(v)) return 0.0;
    sum += coeff[c] * std::max(v, 0.0);
  }
  return sum;
}

// Running CDF of n non-negative values (double sums), rounded to float, 0 first and exactly
// 1 last. A zero total gives the uniform CDF.
void write_cdf(const double* values, int n, float* out) {
  double total = 0;
  for (int i = 0; i < n; ++i) total += values[i];
  out[0] = 0.0f;
  double running = 0;
  for (int i = 1; i < n; ++i) {
    running += values[i - 1];
    out[i] = total > 0.0 ? static_cast<float>(running / total) : static_cast<float>(double(i) / n);
  }
  out[n] = 1.0f;
  // running / total <= 1 in exact arithmetic, and rounding keeps it <= 1 (running <= total),
  // so the sequence is monotone up to the final 1.
}

}  // namespace

std::vector<double> environment_texel_weights(const Image& image) {
  const int w = image.width, h = image.height;
  std::vector<double> lum(static_cast<size_t>(w) * h);
  bool any = false;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double l = texel_luminance(image.at(x, y));
      lum[static_cast<size_t>(y) * w + x] = l;
      any = any || l > 0.0;
    }
  if (!any) std::fill(lum.begin(), lum.end(), 1.0);
  // Mean of the bilinear interpolant over a texel: 1/8, 3/4, 1/8 of the previous, own and
  // next texel along each axis (u repeats, v clamps to the edge row, as the GPU sampler).
  std::vector<double> tmp(lum.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double* row = &lum[static_cast<size_t>(y) * w];
      tmp[static_cast<size_t>(y) * w + x] =
          0.125 * row[(x + w - 1) % w] + 0.75 * row[x] + 0.125 * row[(x + 1) % w];
    }
  std::vector<double> weights(lum.size());
  for (int y = 0; y < h; ++y) {
    const double sin_theta = std::sin(std::numbers::pi * (y + 0.5) / h);
    const double* up = &tmp[static_cast<size_t>(std::max(y - 1, 0)) * w];
    const double* mid = &tmp[static_cast<size_t>(y) * w];
    const double* down = &tmp[static_cast<size_t>(std::min(y + 1, h - 1)) * w];
    for (int x = 0; x < w; ++x)
      weights[static_cast<size_t>(y) * w + x] =
          (0.125 * up[x] + 0.75 * mid[x] + 0.125 * down[x]) * sin_theta;
  }
  return weights;
}

EnvironmentDistribution build_environment_distribution(int width, int height,
                                                       const std::vector<double>& weights) {
  if (width <= 0 || height <= 0 || weights.size() != static_cast<size_t>(width) * height)
    throw std::invalid_argument("build_environment_distribution: size mismatch");
  EnvironmentDistribution d;
  d.width = width;
  d.height = height;
  d.marginal_cdf.resize(height + 1);
  d.conditional_cdf.resize(static_cast<size_t>(height) * (width + 1));
  std::vector<double> row_sums(height);
  for (int y = 0; y < height; ++y) {
    const double* row = &weights[static_cast<size_t>(y) * width];
    double s = 0;
    for (int x = 0; x < width; ++x) s += row[x];
    row_sums[y] = s;
    write_cdf(row, width, &d.conditional_cdf[static_cast<size_t>(y) * (width + 1)]);
  }
  write_cdf(row_sums.data(), height, d.marginal_cdf.data());
  return d;
}

EnvironmentDistribution build_environment_distribution(const Image& image) {
  if (image.width <= 0 || image.height <= 0) return build_environment_distribution(1, 1, {1.0});
  return build_environment_distribution(image.width, image.height,
                                        environment_texel_weights(image));
}

double EnvironmentDistribution::texel_probability(int x, int y) const {
  double row = double(marginal_cdf[y + 1]) - double(marginal_cdf[y]);
  return row * (double(conditional(y, x + 1)) - double(conditional(y, x)));
}

double environment_peak_share(const EnvironmentDistribution& d, double solid_angle_share) {
  struct Texel {
    double radiance, solid_angle, probability;
  };
  std::vector<Texel> texels;
  texels.reserve(static_cast<size_t>(d.width) * static_cast<size_t>(std::max(d.height, 0)));
  const double pi = std::numbers::pi;
  for (int y = 0; y < d.height; ++y) {
    const double solid_angle = 2 * pi * pi / (double(d.width) * d.height) * std::sin(pi * (y + 0.5) / d.height);
    if (!(solid_angle > 0)) continue;
    for (int x = 0; x < d.width; ++x) {
      const double p = d.texel_probability(x, y);
      texels.push_back({p / solid_angle, solid_angle, p});
    }
  }
  const double budget = solid_angle_share * 4 * pi;
  auto brighter = [](const Texel& a, const Texel& b) { return a.radiance > b.radiance; };
  // The brightest texels first: a partial sort of a few times the texels the budget holds on
  // average (enough unless they crowd at the poles, then all of them).
  const size_t few = std::min(texels.size(), static_cast<size_t>(4 * solid_angle_share * texels.size()) + 16);
  for (size_t sorted : {few, texels.size()}) {
    std::partial_sort(texels.begin(), texels.begin() + static_cast<std::ptrdiff_t>(sorted), texels.end(), brighter);
    double covered = 0, share = 0;
    for (size_t i = 0; i < sorted; ++i) {
      const double take = std::min(1.0, (budget - covered) / texels[i].solid_angle);
      covered += take * texels[i].solid_angle;
      share += take * texels[i].probability;
      if (covered >= budget) return share;
    }
  }
  return 1.0;  // the whole sphere is less than the budget
}

PackedEnvironmentDistribution pack_environment_distribution(const EnvironmentDistribution& d) {
  PackedEnvironmentDistribution p;
  p.width = d.width;
  p.height = d.height;
  p.data.reserve(d.marginal_cdf.size() + d.conditional_cdf.size());
  p.data.insert(p.data.end(), d.marginal_cdf.begin(), d.marginal_cdf.end());
  p.data.insert(p.data.end(), d.conditional_cdf.begin(), d.conditional_cdf.end());
  return p;
}

}  // namespace glint
