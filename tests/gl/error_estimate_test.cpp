// The error estimate without a reference (renderer/error_estimate.h) against the true error,
// --target-error's stopping in RenderSession, and adaptive sampling's consistency with uniform
// sampling. Tolerances come from the sample counts (standard errors), never tuned constants.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "gl_test_support.h"
#include "renderer/image_metrics.h"
#include "renderer/render_session.h"
#include "renderer/shader_lib.h"

namespace glint {
namespace {

using test::ensure_gl_context;

// A floor and a ball lit by a small area lamp and a dim sky: soft shadows, a noisy ceiling of
// indirect light, and a range of per-pixel variances.
Scene lamp_scene() {
  Scene s = test::empty_scene();
  s.camera.position = {0, 1.0f, 3.2f};
  s.camera.target = {0, 0.5f, 0};
  s.camera.vfov_deg = 50;
  s.environment.color = {0.1f, 0.12f, 0.15f};
  s.render.max_bounces = 3;
  s.materials.push_back({.name = "floor", .color = {0.7f, 0.7f, 0.7f}});
  s.materials.push_back({.name = "ball", .color = {0.8f, 0.3f, 0.2f}});
  s.materials.push_back({.name = "lamp", .color = {0, 0, 0}, .emission = {12, 10, 8}});
  s.quads.push_back({.name = "floor", .material = "floor",
                     .corners = {glm::vec3{-3, 0, -3}, glm::vec3{-3, 0, 3}, glm::vec3{3, 0, -3}, glm::vec3{3, 0, 3}}});
  s.quads.push_back({.name = "lamp", .material = "lamp",
                     .corners = {glm::vec3{-0.8f, 2, -0.8f}, glm::vec3{-0.8f, 2, 0.4f}, glm::vec3{0.4f, 2, -0.8f}, glm::vec3{0.4f, 2, 0.4f}}});
  s.spheres.push_back({.name = "ball", .center = {0.2f, 0.4f, 0}, .radius = 0.4f, .material = "ball"});
  return s;
}

constexpr int kSize = 32;

struct Render {
  Image mean;
  Image variance;  // rgb: mean squared deviation; a: samples taken
  ErrorEstimate estimate;
};

Render render(Scene scene, RenderOptions options, uint32_t seed, int spp, int batch = 8) {
  ensure_gl_context();
  GpuRenderer r;
  r.set_options(options);
  scene.render.seed = seed;
  r.sync(scene, kSize, kSize);
  for (int done = 0; done < spp; done += batch) r.trace(std::min(batch, spp - done));
  return {r.read_accumulation(), r.read_variance(), r.estimate_error()};
}

// Per-pixel estimates e_i from the read-back textures, through the same shader maths
// (shaders/lib/error_estimate.glsl compiled as C++); -1 where there is none.
std::vector<double> pixel_estimates(const Render& x) {
  std::vector<double> e;
  for (int y = 0; y < kSize; ++y)
    for (int px = 0; px < kSize; ++px) {
      const float* m = x.mean.at(px, y);
      const float* v = x.variance.at(px, y);
      const float finite = v[3] - m[3];
      e.push_back(gpu::estimated_pixel_relmse(glm::vec3(m[0], m[1], m[2]), glm::vec3(v[0], v[1], v[2]), finite));
    }
  return e;
}

// The true relMSE of `image` against a reference of n_ref samples, against the estimate of
// its n samples. E[(m - r)^2] = sigma^2/n + sigma^2/n_ref, so the truth expects the estimate
// times (1 + n / n_ref). Its noise: each pixel's truth term is its estimate times a chi-square
// variable of one degree of freedom (the mean of n samples is close to normal), whose variance
// is 2; the three channels of a pixel may be fully correlated, so a pixel's term has a
// variance of at most 2 e_i^2, and the image mean a standard error of sqrt(sum 2 e_i^2) / P.
// The estimate's own noise (variances of n - 1 degrees of freedom, normal samples: relative
// variance 2 / (n - 1)) adds sqrt(sum 2 e_i^2 / (n - 1)) / P, and its denominator m^2 + 0.01
// in place of r^2 + 0.01 a second-order bias of at most 3 e_i per pixel (relative). The
// tolerance is 4 standard errors plus that bias.
struct Comparison {
  double truth = 0, expected = 0, tolerance = 0;
};
Comparison compare(const Render& x, const Image& reference, int n, int n_ref) {
  const std::vector<double> e = pixel_estimates(x);
  double truth = 0, sum_e = 0, sum_e2 = 0;
  int pixels = 0;
  for (int y = 0; y < kSize; ++y)
    for (int px = 0; px < kSize; ++px) {
      const double ei = e[size_t(y) * kSize + px];
      if (ei < 0) continue;
      const float* m = x.mean.at(px, y);
      const float* r = reference.at(px, y);
      double t = 0;
      for (int c = 0; c < 3; ++c) t += (m[c] - r[c]) * (m[c] - r[c]) / (double(r[c]) * r[c] + kMetricEpsilon);
      truth += t / 3;
      sum_e += ei;
      sum_e2 += ei * ei;
      ++pixels;
    }
  Comparison c;
  const double scale = 1.0 + double(n) / n_ref;
  c.truth = truth / pixels;
  c.expected = sum_e / pixels * scale;
  const double se = std::sqrt(2 * sum_e2 * scale * scale + 2 * sum_e2 / (n - 1)) / pixels;
  c.tolerance = 4 * se + 3 * sum_e2 / pixels * scale;
  return c;
}

TEST(ErrorEstimate, ReductionIsTheMeanOfThePixelEstimates) {
  RenderOptions o;
  const Render x = render(lamp_scene(), o, 3, 32);
  const std::vector<double> e = pixel_estimates(x);
  double sum = 0;
  int n = 0;
  for (double v : e)
    if (v >= 0) sum += v, ++n;
  ASSERT_EQ(x.estimate.pixels, n);
  // Float sums of 16x16 blocks against double: a few float roundings of the total.
  EXPECT_NEAR(x.estimate.relmse, sum / n, 1e-5 * sum / n);
  EXPECT_DOUBLE_EQ(x.estimate.mean_samples, 32.0);  // no sample of this scene is discarded
  for (int i = 0; i < kSize * kSize; ++i) EXPECT_EQ(x.variance.pixels[size_t(i) * 4 + 3], 32.0f);
}

TEST(ErrorEstimate, MatchesTheTrueErrorWithIndependentSamples) {
  RenderOptions pcg;
  pcg.sampler = SamplerKind::pcg;
  constexpr int kSamples = 64, kReference = 2048;
  const Image reference = render(lamp_scene(), pcg, 1000, kReference, 64).mean;
  for (uint32_t seed : {1u, 2u}) {
    const Render x = render(lamp_scene(), pcg, seed, kSamples);
    const Comparison c = compare(x, reference, kSamples, kReference);
    std::printf("seed %u: true relMSE %.4g, estimated %.4g (x %.3f for the reference's noise: %.4g), "
                "tolerance %.3g (a factor of %.3f)\n", seed, c.truth, x.estimate.relmse,
                1 + double(kSamples) / kReference, c.expected, c.tolerance, 1 + c.tolerance / c.expected);
    EXPECT_NEAR(c.truth, c.expected, c.tolerance) << "seed " << seed;
  }
}

// Owen-scrambled Sobol' points (the default sampler) converge faster than independent samples,
// and the estimate assumes independent ones: it may overestimate the error, never underestimate
// it beyond the noise.
TEST(ErrorEstimate, DoesNotUnderestimateTheErrorOfSobolSamples) {
  RenderOptions sobol;
  constexpr int kSamples = 64, kReference = 2048;
  const Image reference = render(lamp_scene(), sobol, 1000, kReference, 64).mean;
  const Render x = render(lamp_scene(), sobol, 1, kSamples);
  const Comparison c = compare(x, reference, kSamples, kReference);
  std::printf("sobol: true relMSE %.4g, estimated %.4g (x %.3f: %.4g), tolerance %.3g\n", c.truth,
              x.estimate.relmse, 1 + double(kSamples) / kReference, c.expected, c.tolerance);
  EXPECT_LE(c.truth, c.expected + c.tolerance);
}

TEST(ErrorEstimate, BothBackendsKeepTheSameVariance) {
  ensure_gl_context();
  Image variance[2];
  for (int b = 0; b < 2; ++b) {
    GpuRendererOptions ro;
    ro.backend = b ? TraceBackend::compute : TraceBackend::fragment;
    GpuRenderer r(ro);
    r.sync(lamp_scene(), kSize, kSize);
    for (int i = 0; i < 4; ++i) r.trace(4);
    variance[b] = r.read_variance();
  }
  EXPECT_EQ(variance[0].pixels, variance[1].pixels);
}

// A constant radiance has no variance: the estimate is 0 but for float rounding of the mean
// (a deviation of a few ulps, 1e-6 relative at most, squared: 1e-12).
TEST(ErrorEstimate, IsZeroForAConstantImage) {
  Scene s = test::empty_scene();
  s.environment.color = {0.3f, 0.6f, 0.9f};
  const Render x = render(s, RenderOptions{}, 1, 40);
  EXPECT_EQ(x.estimate.pixels, kSize * kSize);
  EXPECT_LT(x.estimate.relmse, 1e-12);
}

TEST(ErrorTarget, StopsWhenTheEstimateReachesIt) {
  ensure_gl_context();
  GpuRenderer r;
  r.sync(lamp_scene(), kSize, kSize);
  // The error at 16 spp, halved: relMSE falls as 1/n, so about 32 spp meet it.
  for (int i = 0; i < 4; ++i) r.trace(4);
  const double at16 = r.estimate_error().relmse;
  r.sync(test::empty_scene(), kSize, kSize);
  r.sync(lamp_scene(), kSize, kSize);
  ASSERT_EQ(r.sample_count(), 0);
  RenderSessionOptions o;
  o.target = {.samples = 4096, .seconds = 0, .error = at16 / 2};
  RenderSession session(r, o);
  session.run();
  EXPECT_EQ(session.stop_reason(), StopReason::error);
  EXPECT_LE(session.estimated_relmse(), at16 / 2);
  EXPECT_LE(r.estimate_error().relmse, at16 / 2);
  EXPECT_GE(r.sample_count(), kErrorTargetMinSamples);
  EXPECT_LT(r.sample_count(), 4096);
  EXPECT_EQ(session.progress(), 1.0f);
}

TEST(ErrorTarget, TheSampleCapEndsAnUnreachableTarget) {
  ensure_gl_context();
  GpuRenderer r;
  r.sync(lamp_scene(), kSize, kSize);
  RenderSessionOptions o;
  o.target = {.samples = 24, .seconds = 0, .error = 1e-12};
  RenderSession session(r, o);
  session.run();
  EXPECT_EQ(session.stop_reason(), StopReason::samples);
  EXPECT_EQ(r.sample_count(), 24);
  EXPECT_GT(session.estimated_relmse(), 1e-12);
}

TEST(ErrorTarget, TheTimeCapEndsAnUnreachableTarget) {
  ensure_gl_context();
  GpuRenderer r;
  r.sync(lamp_scene(), kSize, kSize);
  RenderSessionOptions o;
  o.target = {.samples = 0, .seconds = 0.2, .error = 1e-12};
  RenderSession session(r, o);
  session.run();
  EXPECT_EQ(session.stop_reason(), StopReason::time);
  EXPECT_GE(session.seconds(), 0.2);
}

TEST(ErrorTarget, NeedsACap) {
  ensure_gl_context();
  GpuRenderer r;
  r.sync(lamp_scene(), 4, 4);
  RenderSessionOptions o;
  o.target = {.samples = 0, .seconds = 0, .error = 0.01};
  EXPECT_THROW(RenderSession(r, o), std::invalid_argument);
}

// Adaptive sampling converges to the image of uniform sampling: the mean difference of the two
// images, over all pixels and over each quadrant, is within 4 standard errors (from both
// renders' per-pixel variances and sample counts), and it spent fewer samples.
TEST(Adaptive, ConvergesToTheUniformImage) {
  RenderOptions uniform;
  uniform.sampler = SamplerKind::pcg;
  RenderOptions adaptive = uniform;
  adaptive.adaptive = true;
  constexpr int kSamples = 256;
  const Render u = render(lamp_scene(), uniform, 11, kSamples);
  const Render a = render(lamp_scene(), adaptive, 12, kSamples);
  double taken = 0, fewest = 1e30, most = 0;
  for (int i = 0; i < kSize * kSize; ++i) {
    const double n = a.variance.pixels[size_t(i) * 4 + 3];
    taken += n;
    fewest = std::min(fewest, n);
    most = std::max(most, n);
  }
  std::printf("adaptive: %.1f samples per pixel on average (%g to %g), uniform %d\n",
              taken / (kSize * kSize), fewest, most, kSamples);
  EXPECT_LT(taken, 0.9 * kSamples * kSize * kSize);
  EXPECT_EQ(most, kSamples);
  // The floor: the first 16, then at least every 8th pass of 8 samples.
  EXPECT_GE(fewest, 16 + (kSamples - 16) / 8 - 8);
  // Region sums: whole image and quadrants, per channel.
  for (int region = 0; region < 5; ++region)
    for (int c = 0; c < 3; ++c) {
      double difference = 0, variance = 0;
      int pixels = 0;
      for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
          const int quadrant = (y >= kSize / 2) * 2 + (x >= kSize / 2);
          if (region < 4 && quadrant != region) continue;
          const double na = a.variance.at(x, y)[3], nu = u.variance.at(x, y)[3];
          difference += a.mean.at(x, y)[c] - u.mean.at(x, y)[c];
          variance += a.variance.at(x, y)[c] / (na - 1) + u.variance.at(x, y)[c] / (nu - 1);
          ++pixels;
        }
      EXPECT_LE(std::abs(difference), 4 * std::sqrt(variance))
          << "region " << region << " channel " << c << ": " << difference / pixels << " per pixel";
    }
}

// Without adaptive sampling every pixel takes every sample, and turning it on and off restarts
// the accumulation (the pixels' counts would otherwise disagree with the pass count).
TEST(Adaptive, SwitchingItRestartsTheAccumulation) {
  ensure_gl_context();
  GpuRenderer r;
  r.sync(lamp_scene(), 8, 8);
  r.trace(4);
  RenderOptions o;
  o.adaptive = true;
  r.set_options(o);
  EXPECT_TRUE(r.sync(lamp_scene(), 8, 8).accumulation_reset);
}

}  // namespace
}  // namespace glint
