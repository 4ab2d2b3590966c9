// "The same picture": a scene moved or scaled as a whole, rendered with the same seed, must
// give the image of the original within the noise of its sample count. Shared by the hard
// cases of tests/gl/render_precision_test.cpp and tests/gl/manifold_nee_test.cpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "renderer/image.h"
#include "renderer/image_metrics.h"
#include "renderer/scene.h"
#include "tests/gl/gl_test_support.h"

namespace glint::test {

// Every position scaled by `scale` and then moved by `offset`: the same picture.
inline Scene transformed(Scene s, float scale, glm::vec3 offset) {
  auto map = [&](glm::vec3 p) { return scale * p + offset; };
  s.camera.position = map(s.camera.position);
  s.camera.target = map(s.camera.target);
  s.camera.focus_distance *= scale;
  s.camera.aperture_radius *= scale;
  for (Sphere& sp : s.spheres) {
    sp.center = map(sp.center);
    sp.radius *= scale;
  }
  for (Quad& q : s.quads)
    for (glm::vec3& c : q.corners) c = map(c);
  return s;
}

inline double luminance_at(const Image& img, int x, int y) {
  const float* p = img.at(x, y);
  return luminance(p[0], p[1], p[2]);
}

// How image b differs from image a (same seed), against the noise of the sample count: `noise`
// is the RMS per-pixel luminance difference between a and a render of the same scene with
// another seed (sqrt(2) times the per-pixel standard deviation).
struct Agreement {
  double mean_difference = 0;  // mean over pixels of lum(b) - lum(a)
  double rms_difference = 0;
  double noise = 0;            // RMS of lum(a) - lum(a with another seed)
  double mean_standard_error = 0;  // of an image mean, from `noise`: noise / sqrt(2 pixels)
  double mean_a = 0;
};

inline Agreement agreement(const Image& a, const Image& b, const Image& a_other_seed) {
  Agreement r;
  const int n = a.width * a.height;
  double s = 0, s2 = 0, noise2 = 0, sa = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const double d = luminance_at(b, x, y) - luminance_at(a, x, y);
      const double e = luminance_at(a_other_seed, x, y) - luminance_at(a, x, y);
      s += d;
      s2 += d * d;
      noise2 += e * e;
      sa += luminance_at(a, x, y);
    }
  r.mean_difference = s / n;
  r.rms_difference = std::sqrt(s2 / n);
  r.noise = std::sqrt(noise2 / n);
  r.mean_standard_error = r.noise / std::sqrt(2.0 * n);
  r.mean_a = sa / n;
  return r;
}

inline double max_alpha(const Image& img) {
  double m = 0;
  for (size_t i = 3; i < img.pixels.size(); i += 4) m = std::max(m, double(img.pixels[i]));
  return m;
}

// The images agree within the noise of their sample count: the image means within 4 standard
// errors, and no more per-pixel difference than an independent render has (the same seed
// draws the same random numbers, so a correct transformed render is closer than that; acne,
// black speckles or light leaks add differences of the size of the signal).
inline void expect_agreement(const Image& a, const Image& b, const Image& a_other_seed, const char* what) {
  ASSERT_TRUE(all_finite(b)) << what;
  EXPECT_EQ(max_alpha(b), 0.0) << what << ": discarded samples";
  Agreement g = agreement(a, b, a_other_seed);
  std::printf("%s: mean %.5g, mean diff %.3g (4 SE %.3g), rms diff %.3g, seed noise %.3g\n", what,
              g.mean_a, g.mean_difference, 4 * g.mean_standard_error, g.rms_difference, g.noise);
  EXPECT_LT(std::abs(g.mean_difference), 4.0 * g.mean_standard_error) << what;
  EXPECT_LT(g.rms_difference, g.noise) << what;
}

}  // namespace glint::test
