// Shared set-up for GL tests: one headless context per process, small scenes, image stats.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "renderer/gl_context.h"
#include "renderer/gpu_renderer.h"
#include "renderer/image.h"
#include "renderer/scene.h"

namespace glint::test {

// The process's context, created and made current on first use.
inline HeadlessGLContext& ensure_gl_context() {
  static std::unique_ptr<HeadlessGLContext> context = HeadlessGLContext::create();
  return *context;
}

// A camera looking down -Z at the origin from z = 5, with a black environment.
inline Scene empty_scene() {
  Scene s;
  s.camera.position = {0, 0, 5};
  s.camera.target = {0, 0, 0};
  s.camera.up = {0, 1, 0};
  s.environment.color = {0, 0, 0};
  return s;
}

struct Stats {
  double mean = 0;
  double variance = 0;  // of the per-pixel values
  int count = 0;
};

// Statistics of channel c over the pixels where `use(x, y)` is true.
template <typename Pred>
Stats channel_stats(const Image& img, int c, Pred use) {
  Stats s;
  double sum = 0, sum2 = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (use(x, y)) {
        double v = img.at(x, y)[c];
        sum += v;
        sum2 += v * v;
        ++s.count;
      }
  if (s.count > 0) {
    s.mean = sum / s.count;
    s.variance = std::max(0.0, sum2 / s.count - s.mean * s.mean);
  }
  return s;
}

// The largest difference of a colour channel between two images, relative to b's value (at
// least 1e-3); alpha (the discarded-sample count) is skipped.
inline double max_relative_difference(const Image& a, const Image& b) {
  double worst = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    double d = std::abs(double(a.pixels[i]) - b.pixels[i]);
    worst = std::max(worst, d / std::max(1e-3, std::abs(double(b.pixels[i]))));
  }
  return worst;
}

inline bool all_finite(const Image& img) {
  for (float v : img.pixels)
    if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace glint::test
