// Next-event estimation with MIS, Russian roulette and the Sobol sampler change the noise, not
// the expected image: rendered by the GPU path tracer against the original estimator (BSDF
// sampling only, no roulette) on a small scene with every case the shadow rays must handle:
// an emitting sphere and quad, a cut-out (coverage 0.5) and a smooth thin glass pane in front
// of the quad light, rough glass and glossy spheres. Tolerances: 4 standard errors of the
// difference of two image means (regions of the image), each standard error measured from two
// independent renders of the same estimator.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "renderer/shader_features.h"
#include "tests/gl/gl_test_support.h"

namespace glint {
namespace {

using test::all_finite;
using test::empty_scene;
using test::ensure_gl_context;

Scene lit_scene() {
  Scene s = empty_scene();
  s.camera.position = {0, 1.0f, 3.2f};
  s.camera.target = {0, 0.5f, 0};
  s.camera.vfov_deg = 50;
  s.environment.color = {0.1f, 0.12f, 0.15f};
  s.render.max_bounces = 4;
  s.materials.push_back({.name = "floor", .color = {0.7f, 0.7f, 0.7f}});
  s.materials.push_back({.name = "lamp", .color = {0, 0, 0}, .emission = {12, 10, 8}});
  s.materials.push_back({.name = "bulb", .color = {0, 0, 0}, .emission = {200, 200, 150}});
  s.materials.push_back({.name = "cutout", .color = {0.9f, 0.2f, 0.2f}, .opacity = 0.5f});
  s.materials.push_back({.name = "pane", .type = MaterialType::transparent, .color = {0.6f, 0.9f, 0.6f}});
  s.materials.push_back({.name = "frosted", .type = MaterialType::transparent, .color = {1, 1, 1}, .roughness = 0.4f});
  s.materials.push_back({.name = "gloss", .type = MaterialType::glossy, .color = {0.2f, 0.3f, 0.8f}, .roughness = 0.3f});
  s.quads.push_back({.name = "floor", .material = "floor",
                     .corners = {glm::vec3{-3, 0, -3}, glm::vec3{-3, 0, 3}, glm::vec3{3, 0, -3}, glm::vec3{3, 0, 3}}});
  s.quads.push_back({.name = "lamp", .material = "lamp",
                     .corners = {glm::vec3{-0.8f, 2, -0.8f}, glm::vec3{-0.8f, 2, 0.4f}, glm::vec3{0.4f, 2, -0.8f}, glm::vec3{0.4f, 2, 0.4f}}});
  // Half of the lamp is seen through a cut-out, part of the rest through a glass pane.
  s.quads.push_back({.name = "cutout", .material = "cutout",
                     .corners = {glm::vec3{-1, 1.6f, -1}, glm::vec3{-1, 1.6f, 0}, glm::vec3{-0.2f, 1.6f, -1}, glm::vec3{-0.2f, 1.6f, 0}}});
  s.quads.push_back({.name = "pane", .material = "pane",
                     .corners = {glm::vec3{-0.2f, 1.5f, -1}, glm::vec3{-0.2f, 1.5f, 0.6f}, glm::vec3{0.6f, 1.5f, -1}, glm::vec3{0.6f, 1.5f, 0.6f}}});
  s.spheres.push_back({.name = "bulb", .center = {0.9f, 0.9f, 0.2f}, .radius = 0.08f, .material = "bulb"});
  s.spheres.push_back({.name = "frosted", .center = {-0.5f, 0.35f, 0.3f}, .radius = 0.35f, .material = "frosted"});
  s.spheres.push_back({.name = "gloss", .center = {0.45f, 0.3f, -0.2f}, .radius = 0.3f, .material = "gloss"});
  return s;
}

constexpr int kSize = 32;
constexpr int kRegions = 4;  // 4 x 4 regions of 8 x 8 pixels

Image render(const Scene& scene, const RenderOptions& options, int spp, uint32_t seed) {
  Scene s = scene;
  s.render.seed = seed;
  GpuRenderer r;
  r.set_options(options);
  r.sync(s, kSize, kSize);
  for (int done = 0; done < spp; done += 64) r.trace(64);
  return r.read_accumulation();
}

// Mean luminance of each region, and the standard error of that mean from two seeds: the
// per-pixel difference of two independent renders has variance 2 sigma^2.
struct RegionMeans {
  double mean[kRegions * kRegions] = {};
  double standard_error[kRegions * kRegions] = {};
};

double lum(const Image& img, int x, int y) {
  const float* p = img.at(x, y);
  return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

RegionMeans region_means(const Image& a, const Image& b) {
  RegionMeans r;
  const int side = kSize / kRegions, n = side * side;
  for (int ry = 0; ry < kRegions; ++ry)
    for (int rx = 0; rx < kRegions; ++rx) {
      double s = 0, d2 = 0;
      for (int y = ry * side; y < (ry + 1) * side; ++y)
        for (int x = rx * side; x < (rx + 1) * side; ++x) {
          s += 0.5 * (lum(a, x, y) + lum(b, x, y));
          const double d = lum(a, x, y) - lum(b, x, y);
          d2 += d * d;
        }
      // Mean of 2n pixel values with per-pixel variance sigma^2 = E[d^2] / 2.
      r.mean[ry * kRegions + rx] = s / n;
      r.standard_error[ry * kRegions + rx] = std::sqrt(d2 / n / 2.0 / (2.0 * n));
    }
  return r;
}

// The original program's estimator: BSDF sampling only, no roulette, independent PCG numbers
// (the reference of the tests below: an estimator that shares no technique with those tested).
RenderOptions bsdf_only() {
  RenderOptions o;
  o.light_sampling = o.environment_sampling = o.russian_roulette = false;
  o.sampler = SamplerKind::pcg;
  return o;
}

void expect_same_expectation(const RegionMeans& a, const RegionMeans& b, const char* what) {
  for (int i = 0; i < kRegions * kRegions; ++i) {
    const double se = std::hypot(a.standard_error[i], b.standard_error[i]);
    EXPECT_NEAR(a.mean[i], b.mean[i], 4.0 * se) << what << ", region " << i;
  }
}

struct Renders {
  RegionMeans bsdf, nee;
};
const Renders& renders() {
  static Renders r = [] {
    Scene s = lit_scene();
    Renders out;
    out.bsdf = region_means(render(s, bsdf_only(), 1024, 1), render(s, bsdf_only(), 1024, 2));
    Image n1 = render(s, RenderOptions{}, 256, 1), n2 = render(s, RenderOptions{}, 256, 2);
    EXPECT_TRUE(all_finite(n1) && all_finite(n2));
    out.nee = region_means(n1, n2);
    return out;
  }();
  return r;
}

TEST(LightSampling, AgreesWithBsdfSamplingThroughCutoutsAndGlass) {
  ensure_gl_context();
  const Renders& r = renders();
  expect_same_expectation(r.bsdf, r.nee, "light sampling + MIS + roulette vs BSDF sampling");
  // And it is the point of it: less noise per sample. Over the image, the standard error at
  // 256 spp with light sampling is below that of BSDF sampling at 1024 spp.
  double se_bsdf = 0, se_nee = 0;
  for (int i = 0; i < kRegions * kRegions; ++i) {
    se_bsdf += r.bsdf.standard_error[i];
    se_nee += r.nee.standard_error[i];
  }
  std::printf("mean region standard error: BSDF sampling 1024 spp %.4g, light sampling 256 spp %.4g\n",
              se_bsdf / 16, se_nee / 16);
  EXPECT_LT(se_nee, se_bsdf);
}

TEST(LightSampling, SobolSamplerIsUnbiased) {
  ensure_gl_context();
  RenderOptions sobol;
  sobol.sampler = SamplerKind::sobol;
  Scene s = lit_scene();
  RegionMeans m = region_means(render(s, sobol, 256, 1), render(s, sobol, 256, 2));
  expect_same_expectation(renders().bsdf, m, "Sobol vs BSDF sampling");
}

// Direct light only (the bench's direct-light case): a matte floor and ball under the quad lamp
// and a dim sky, max_bounces 1, the lamp itself out of view, so that pixel values have no heavy
// tail (no caustics) and the sums below are dominated by no single pixel.
Scene direct_light_scene() {
  Scene s = empty_scene();
  s.camera.position = {0, 1.0f, 3.2f};
  s.camera.target = {0, 0.5f, 0};
  s.camera.vfov_deg = 30;  // the lamp (whose edges would hold most of the variance) out of view
  s.environment.color = {0.1f, 0.12f, 0.15f};
  s.render.max_bounces = 1;
  s.materials.push_back({.name = "floor", .color = {0.7f, 0.7f, 0.7f}});
  s.materials.push_back({.name = "lamp", .color = {0, 0, 0}, .emission = {12, 10, 8}});
  s.materials.push_back({.name = "ball", .color = {0.8f, 0.3f, 0.2f}});
  s.quads.push_back({.name = "floor", .material = "floor",
                     .corners = {glm::vec3{-3, 0, -3}, glm::vec3{-3, 0, 3}, glm::vec3{3, 0, -3}, glm::vec3{3, 0, 3}}});
  s.quads.push_back({.name = "lamp", .material = "lamp",
                     .corners = {glm::vec3{-0.8f, 2, -0.8f}, glm::vec3{-0.8f, 2, 0.4f}, glm::vec3{0.4f, 2, -0.8f}, glm::vec3{0.4f, 2, 0.4f}}});
  s.spheres.push_back({.name = "ball", .center = {0.1f, 0.4f, 0.1f}, .radius = 0.4f, .material = "ball"});
  return s;
}

// The lamp sampled by the affine map of a parallelogram and by the two-triangle sampler (its
// fourth corner moved 2e-5 of its size out of the parallelogram, beyond quad_is_parallelogram's
// 2^-21, so that the light table and the program take the triangles; the image changes by about
// that fraction) has the same expected image: the two samplers share one density. Sobol, 256
// spp, two seeds each; tolerance 4 standard errors per region, as above.
TEST(LightSampling, ParallelogramSamplerAgreesWithTheTriangleSampler) {
  ensure_gl_context();
  const Scene parallelogram = direct_light_scene();
  Scene triangles = parallelogram;
  triangles.quads[1].corners[3] += glm::vec3(2e-5f, 0, 2e-5f);
  ASSERT_FALSE(scene_features(parallelogram).has_general_quad_lights);
  ASSERT_TRUE(scene_features(triangles).has_general_quad_lights);
  RenderOptions sobol;
  sobol.sampler = SamplerKind::sobol;
  const Image a1 = render(parallelogram, sobol, 256, 1), a2 = render(parallelogram, sobol, 256, 2);
  const Image b1 = render(triangles, sobol, 256, 1), b2 = render(triangles, sobol, 256, 2);
  double differing = 0;
  for (size_t i = 0; i < a1.pixels.size(); ++i) differing += a1.pixels[i] != b1.pixels[i];
  EXPECT_GT(differing, a1.pixels.size() / 4) << "the two samplers must draw different points";
  expect_same_expectation(region_means(a1, a2), region_means(b1, b2), "parallelogram vs triangles");
}

// The seed spread of Sobol renders is their error, as bench/ and the error bars assume: each seed
// is an independent randomisation, so the per-pixel variance across seeds is the variance of
// one render. 2K = 32 seeds at 16 spp, on the direct-light scene above. Two statistics over the
// P = 1024 pixels, each a ratio of weighted sums of per-pixel squares (chi-square distributed
// for normal pixel values), and both 1 in expectation when the seeds are independent:
//  T1 = sum w (A - B)^2 / sum w 2 s^2 / K: the means A, B of two groups of K seeds against the
//       pooled within-group variance s^2 (2K - 2 degrees of freedom per pixel); seeds
//       correlated within a group make the group means disagree more than s^2 says, seeds
//       correlated across the groups make them agree more;
//  T2 = sum w (M - R)^2 / sum w (s^2 / 2K + v): the mean M of all 2K seeds against an
//       independent PCG reference R (two renders of 512 spp, whose per-pixel variance of the
//       mean v is estimated as (R1 - R2)^2 / 4); a component all seeds share (a bias, or a
//       correlation common to every seed) makes M miss R by more than the spread says.
// The weights w = 1 / variance come from 16 further seeds (independent of both sums, so each
// sum keeps its expectation) and spread the statistic over all pixels instead of the few
// edge pixels that hold most of Sobol's variance. Tolerance: 4 standard deviations of each
// ratio, from the delta method with the variance of each sum bounded by the sum of its terms'
// squares (Var X <= E X^2, estimated per pixel).
TEST(LightSampling, SobolSeedSpreadIsItsError) {
  ensure_gl_context();
  constexpr int kHalf = 16, kWeightSeeds = 16, kSpp = 16;
  RenderOptions sobol;
  sobol.sampler = SamplerKind::sobol;
  RenderOptions pcg;
  pcg.sampler = SamplerKind::pcg;
  const Scene s = direct_light_scene();
  auto render_spp = [&](const RenderOptions& o, int spp, uint32_t seed) {
    Scene v = s;
    v.render.seed = seed;
    GpuRenderer r;
    r.set_options(o);
    r.sync(v, kSize, kSize);
    r.trace(spp);
    return r.read_accumulation();
  };
  std::vector<Image> images, weight_images;
  for (int k = 0; k < 2 * kHalf; ++k) images.push_back(render_spp(sobol, kSpp, 100 + uint32_t(k)));
  for (int k = 0; k < kWeightSeeds; ++k) weight_images.push_back(render_spp(sobol, kSpp, 200 + uint32_t(k)));
  const Image r1 = render(s, pcg, 512, 901), r2 = render(s, pcg, 512, 902);
  // Per-pixel variance across the weight seeds; a floor of its image mean keeps pixels whose
  // 16 weight seeds happened to agree from taking all the weight.
  std::vector<double> var_w(kSize * kSize);
  double mean_var_w = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      double m = 0, ss = 0;
      for (const Image& im : weight_images) m += lum(im, x, y) / kWeightSeeds;
      for (const Image& im : weight_images) ss += std::pow(lum(im, x, y) - m, 2);
      var_w[y * kSize + x] = ss / (kWeightSeeds - 1);
      mean_var_w += var_w[y * kSize + x] / (kSize * kSize);
    }
  ASSERT_GT(mean_var_w, 0);
  double n1 = 0, d1 = 0, n1_sq = 0, d1_sq = 0, n2 = 0, d2 = 0, n2_sq = 0, d2_sq = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const double w = 1 / (var_w[y * kSize + x] + mean_var_w);
      double a = 0, b = 0;
      for (int k = 0; k < kHalf; ++k) {
        a += lum(images[k], x, y) / kHalf;
        b += lum(images[kHalf + k], x, y) / kHalf;
      }
      double ss = 0;
      for (int k = 0; k < kHalf; ++k) {
        ss += std::pow(lum(images[k], x, y) - a, 2) + std::pow(lum(images[kHalf + k], x, y) - b, 2);
      }
      const double s2 = ss / (2 * kHalf - 2);
      const double t1n = w * (a - b) * (a - b), t1d = w * 2 * s2 / kHalf;
      const double m = 0.5 * (a + b), ref = 0.5 * (lum(r1, x, y) + lum(r2, x, y));
      const double v = std::pow(lum(r1, x, y) - lum(r2, x, y), 2) / 4;
      const double t2n = w * (m - ref) * (m - ref), t2d = w * (s2 / (2 * kHalf) + v);
      n1 += t1n, d1 += t1d, n1_sq += t1n * t1n, d1_sq += t1d * t1d;
      n2 += t2n, d2 += t2d, n2_sq += t2n * t2n, d2_sq += t2d * t2d;
    }
  const double t1 = n1 / d1, sd1 = t1 * std::sqrt(n1_sq / (n1 * n1) + d1_sq / (d1 * d1));
  const double t2 = n2 / d2, sd2 = t2 * std::sqrt(n2_sq / (n2 * n2) + d2_sq / (d2 * d2));
  std::printf("Sobol seeds: T1 (between / within groups) %.3f +- %.3f, T2 (mean vs PCG reference) %.3f +- %.3f\n",
              t1, sd1, t2, sd2);
  EXPECT_NEAR(t1, 1.0, 4 * sd1);
  EXPECT_NEAR(t2, 1.0, 4 * sd2);
}

TEST(LightSampling, FireflyClampOnlyDarkens) {
  ensure_gl_context();
  RenderOptions clamped;
  clamped.clamp = 1.0f;
  Scene s = lit_scene();
  Image c = render(s, clamped, 64, 1), u = render(s, RenderOptions{}, 64, 1);
  // Same seed and random numbers: every pixel is at most its unclamped value, and no sample
  // is brighter than the clamp, so no pixel mean is either.
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      EXPECT_LE(lum(c, x, y), lum(u, x, y) * (1 + 1e-5) + 1e-6) << x << "," << y;
      EXPECT_LE(lum(c, x, y), 1.0 + 1e-4) << x << "," << y;
    }
}

// An environment map with a small bright sun (about 2 x 2 texels of 64 x 32 at 2000 times the
// sky) over a matte floor and a rough metal sphere: importance-sampling the map (with MIS
// against BSDF sampling) must give the image BSDF sampling gives, and with far less noise.
TEST(LightSampling, EnvironmentSamplingAgreesWithBsdfSampling) {
  ensure_gl_context();
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("glint-gl-env-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Image sky;
  sky.width = 64;
  sky.height = 32;
  sky.pixels.assign(64 * 32 * 4, 1.0f);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      float* p = &sky.pixels[(y * 64 + x) * 4];
      p[0] = 0.3f + 0.01f * y;
      p[1] = 0.4f;
      p[2] = 0.6f - 0.01f * y;
      if ((x == 20 || x == 21) && (y == 9 || y == 10)) p[0] = p[1] = p[2] = 1000.0f;
    }
  save_image(dir / "sky.exr", sky);
  Scene s = empty_scene();
  s.base_dir = dir;
  s.environment.texture = "sky.exr";
  s.environment.rotation_deg = 30;
  s.camera.position = {0, 1.0f, 3.0f};
  s.camera.target = {0, 0.4f, 0};
  s.render.max_bounces = 3;
  s.materials.push_back({.name = "floor", .color = {0.6f, 0.6f, 0.6f}});
  s.materials.push_back({.name = "metal", .type = MaterialType::reflective, .color = {0.9f, 0.8f, 0.6f}, .roughness = 0.35f});
  s.quads.push_back({.name = "floor", .material = "floor",
                     .corners = {glm::vec3{-3, 0, -3}, glm::vec3{-3, 0, 3}, glm::vec3{3, 0, -3}, glm::vec3{3, 0, 3}}});
  s.spheres.push_back({.name = "metal", .center = {0, 0.5f, 0}, .radius = 0.5f, .material = "metal"});
  RegionMeans bsdf = region_means(render(s, bsdf_only(), 1024, 1), render(s, bsdf_only(), 1024, 2));
  RegionMeans env = region_means(render(s, RenderOptions{}, 256, 1), render(s, RenderOptions{}, 256, 2));
  fs::remove_all(dir);
  expect_same_expectation(bsdf, env, "environment sampling vs BSDF sampling");
  double se_bsdf = 0, se_env = 0;
  for (int i = 0; i < kRegions * kRegions; ++i) {
    se_bsdf += bsdf.standard_error[i];
    se_env += env.standard_error[i];
  }
  std::printf("mean region standard error: BSDF sampling 1024 spp %.4g, environment sampling 256 spp %.4g\n",
              se_bsdf / 16, se_env / 16);
  EXPECT_LT(se_env, se_bsdf);
}

}  // namespace
}  // namespace glint
