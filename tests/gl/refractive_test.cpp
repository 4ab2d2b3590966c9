// The refractive material rendered by the GPU path tracer (headless EGL; llvmpipe in CI):
// white furnaces, where every path's weight is exactly 1 so that each sample equals the
// environment (a clear interface conserves energy and the 1 / eta^2 of entering cancels the
// eta^2 of leaving), the camera inside a ball, ior 1, next-event estimation around glass
// (unbiased: it agrees with BSDF sampling alone), and the hard cases (tiny and huge balls far
// from the origin, a ball touching a quad, a ball inside a ball).
#include <cmath>
#include <string>

#include "renderer/scene_fields.h"
#include "tests/gl/gl_test_support.h"

namespace glint {
namespace {

using test::empty_scene;
using test::ensure_gl_context;

constexpr float kEnv = 0.6f;

Image render(const Scene& scene, int w, int h, int spp, const RenderOptions& options) {
  GpuRenderer r;
  r.set_options(options);
  r.sync(scene, w, h);
  r.trace(spp);
  return r.read_accumulation();
}

// Russian roulette off, so that a path's weight is the product of its BSDF weights alone.
RenderOptions no_roulette() {
  RenderOptions o;
  o.russian_roulette = false;
  return o;
}

Scene furnace(glm::vec3 camera, glm::vec3 target, float vfov_deg) {
  Scene s = empty_scene();
  s.camera.position = camera;
  s.camera.target = target;
  s.camera.vfov_deg = vfov_deg;
  s.environment.color = {kEnv, kEnv, kEnv};
  s.render.max_bounces = kMaxBounces;
  return s;
}

void add_glass(Scene& s, const std::string& name, float ior, float roughness = 0) {
  s.materials.push_back({.name = name, .type = MaterialType::refractive, .color = {1, 1, 1},
                         .roughness = roughness, .ior = ior});
}

// Every pixel of a furnace within `relative` of `expected` (all channels), and the count of
// pixels that showed glass is reported by `glass_pixels` (those that differ from a render
// without it would need another render; the caller frames the glass to fill the view).
// Tolerance: each sample is the environment times the product of its weights, at most 1024
// pairs 1 / eta^2 and eta^2 (and weights 1), each exact to a few float eps; the paths of these
// scenes take a handful of bounces, so 1e-4 (about 800 eps) bounds their rounding, while a
// wrong side (ior where 1 / ior is due) is off by a factor eta^2 on every sample that makes it.
void expect_every_pixel(const Image& img, double expected, double relative, const char* what) {
  ASSERT_TRUE(test::all_finite(img)) << what;
  double worst = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(img.at(x, y)[c] / expected - 1));
  EXPECT_LE(worst, relative) << what << ": worst pixel off by " << worst << " (relative)";
  EXPECT_EQ(test::channel_stats(img, 3, [](int, int) { return true; }).mean, 0.0)
      << what << ": discarded samples";
}

// A clear smooth ball in a uniform environment is invisible: every pixel is the environment,
// for glass (1.5), a high index (2.4), an index below 1 (0.8) and ior 1.
TEST(GlRefractive, ClearBallInAFurnaceIsTheEnvironment) {
  ensure_gl_context();
  for (float ior : {1.5f, 2.4f, 0.8f, 1.0f}) {
    SCOPED_TRACE("ior " + std::to_string(ior));
    Scene s = furnace({0, 0, 3}, {0, 0, 0}, 45);
    add_glass(s, "glass", ior);
    s.spheres.push_back({.center = {0, 0, 0}, .radius = 1, .material = "glass"});
    expect_every_pixel(render(s, 24, 24, 32, no_roulette()), kEnv, 1e-4, "clear ball");
  }
}

// With Russian roulette on, the clear ball is still exactly the environment, every sample: a
// path inside it carries 1 / ior^2 of its weight, which the roulette's survival probability
// undoes (eta_scale in continue_path), so no path is ever killed or reweighted. Without that term
// a path inside the ball survives each roulette step with probability 1 / ior^2, and the worst
// pixel was 3.9% off for ior 1.5 and 15% for 2.4 (ior 0.8 < 1 keeps survival at 1 either way).
TEST(GlRefractive, RouletteLeavesAClearBallInAFurnaceExact) {
  ensure_gl_context();
  for (float ior : {1.5f, 2.4f, 0.8f}) {
    SCOPED_TRACE("ior " + std::to_string(ior));
    Scene s = furnace({0, 0, 3}, {0, 0, 0}, 45);
    add_glass(s, "glass", ior);
    s.spheres.push_back({.center = {0, 0, 0}, .radius = 1, .material = "glass"});
    RenderOptions with_roulette;
    with_roulette.russian_roulette = true;
    expect_every_pixel(render(s, 24, 24, 32, with_roulette), kEnv, 1e-4, "clear ball, roulette on");
  }
}

// Rough glass loses the light that its microfacets shadow (single scattering), never gains:
// the image mean is at most the environment, within 4 standard errors of the pixel mean.
TEST(GlRefractive, RoughBallInAFurnaceCreatesNoEnergy) {
  ensure_gl_context();
  for (float roughness : {0.2f, 0.6f}) {
    Scene s = furnace({0, 0, 3}, {0, 0, 0}, 45);
    add_glass(s, "glass", 1.5f, roughness);
    s.spheres.push_back({.center = {0, 0, 0}, .radius = 1, .material = "glass"});
    Image img = render(s, 24, 24, 64, RenderOptions{});
    ASSERT_TRUE(test::all_finite(img));
    test::Stats st = test::channel_stats(img, 1, [](int, int) { return true; });
    EXPECT_LE(st.mean, kEnv + 4 * std::sqrt(st.variance / st.count)) << "roughness " << roughness;
    EXPECT_GT(st.mean, 0.5 * kEnv) << "roughness " << roughness;
  }
}

// A camera inside a clear ball sees the uniform environment brighter by ior^2: radiance over
// the squared index is what a ray carries across the interface, and every path leaves once.
TEST(GlRefractive, CameraInsideABallSeesTheEnvironmentTimesIorSquared) {
  ensure_gl_context();
  for (float ior : {1.5f, 0.8f}) {
    SCOPED_TRACE("ior " + std::to_string(ior));
    Scene s = furnace({0.2f, 0.1f, 0.3f}, {0, 0, -1}, 90);
    add_glass(s, "glass", ior);
    s.spheres.push_back({.center = {0, 0, 0}, .radius = 1, .material = "glass"});
    expect_every_pixel(render(s, 16, 16, 32, no_roulette()), kEnv * ior * ior, 1e-4, "inside");
  }
}

// ior 1: the smooth ball vanishes. An emitting quad (black otherwise) partly behind a ball
// that covers its edges looks the same with and without the ball: same camera rays (the pixel
// jitter is the first sample dimension in both), unbent. Only rays within rounding of the
// quad's edge can differ: at most one pixel row or column's share of samples.
TEST(GlRefractive, IorOneBallVanishes) {
  ensure_gl_context();
  Scene s = empty_scene();
  s.materials.push_back({.name = "lamp", .color = {0, 0, 0}, .emission = {1, 1, 1}});
  s.quads.push_back({.material = "lamp", .corners = {glm::vec3(-0.5f, -0.5f, -1), glm::vec3(-0.5f, 3, -1),
                                                     glm::vec3(3, -0.5f, -1), glm::vec3(3, 3, -1)}});
  const int w = 32, h = 32;
  Image without = render(s, w, h, 16, no_roulette());
  add_glass(s, "air_glass", 1.0f);
  s.spheres.push_back({.center = {-0.3f, -0.2f, 0}, .radius = 0.8f, .material = "air_glass"});
  Image with = render(s, w, h, 16, no_roulette());
  double differing = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) differing += std::abs(with.at(x, y)[0] - without.at(x, y)[0]);
  EXPECT_LE(differing, double(w + h)) << "summed |difference| over the image";
  test::Stats lit = test::channel_stats(with, 0, [](int, int) { return true; });
  EXPECT_GT(lit.mean, 0.2);
  EXPECT_LT(lit.mean, 0.8);
}

// Image mean and its standard error over `seeds` independent renders (the spread of the seeds'
// means: each seed is an independent randomisation).
std::pair<double, double> mean_over_seeds(Scene s, int w, int h, int spp, const RenderOptions& o, int seeds) {
  double sum = 0, sum2 = 0;
  for (int k = 0; k < seeds; ++k) {
    s.render.seed = uint32_t(100 + k);
    Image img = render(s, w, h, spp, o);
    EXPECT_TRUE(test::all_finite(img));
    double m = test::channel_stats(img, 1, [](int, int) { return true; }).mean;
    sum += m;
    sum2 += m * m;
  }
  double mean = sum / seeds;
  double var = std::max(0.0, (sum2 - seeds * mean * mean) / (seeds - 1));
  return {mean, std::sqrt(var / seeds)};
}

// Next-event estimation with glass in the scene is unbiased: shadow rays stop at refractive
// surfaces (the light behind them comes by BSDF sampling alone), and rough glass samples lights
// on both sides of its surface. A matte floor lit by a quad light through and around a smooth
// and a rough glass ball: the image mean with light sampling agrees with BSDF sampling alone
// within 4 standard errors of the difference (8 seeds each).
TEST(GlRefractive, LightSamplingAroundGlassAgreesWithBsdfSampling) {
  ensure_gl_context();
  for (float roughness : {0.0f, 0.3f}) {
    SCOPED_TRACE("roughness " + std::to_string(roughness));
    Scene s = empty_scene();
    s.camera.position = {0, 1.5f, 4};
    s.camera.target = {0, 0.5f, 0};
    s.render.max_bounces = 8;
    s.materials.push_back({.name = "floor", .color = {0.8f, 0.8f, 0.8f}});
    s.materials.push_back({.name = "lamp", .color = {0, 0, 0}, .emission = {6, 6, 6}});
    add_glass(s, "glass", 1.5f, roughness);
    s.quads.push_back({.material = "floor", .corners = {glm::vec3(-3, 0, -3), glm::vec3(-3, 0, 3),
                                                        glm::vec3(3, 0, -3), glm::vec3(3, 0, 3)}});
    s.quads.push_back({.material = "lamp", .corners = {glm::vec3(-1, 3, -1), glm::vec3(1, 3, -1),
                                                       glm::vec3(-1, 3, 1), glm::vec3(1, 3, 1)}});
    s.spheres.push_back({.center = {0, 0.8f, 0}, .radius = 0.8f, .material = "glass"});
    RenderOptions bsdf_only;
    bsdf_only.light_sampling = false;
    auto [with_nee, se_nee] = mean_over_seeds(s, 20, 16, 32, RenderOptions{}, 8);
    auto [without, se_bsdf] = mean_over_seeds(s, 20, 16, 32, bsdf_only, 8);
    EXPECT_NEAR(with_nee, without, 4 * std::hypot(se_nee, se_bsdf))
        << "NEE " << with_nee << " +- " << se_nee << ", BSDF only " << without << " +- " << se_bsdf;
    EXPECT_GT(with_nee, 0.05);
  }
}

// Hard cases, each a furnace with every path's weight exactly 1: a tiny ball (radius 1e-3) and
// a huge one (1e4) far from the origin, a clear ball resting on a white matte quad (albedo 1,
// weight 1 per bounce), and a ball inside a ball (each interface air to glass, as in Mitsuba;
// every path crosses each one in and out equally often).
TEST(hard_Refractive, TinyAndHugeBallsFarFromTheOrigin) {
  ensure_gl_context();
  struct Case {
    const char* name;
    glm::vec3 center;
    float radius;
  };
  for (const Case& c : {Case{"tiny", {1e3f, -2e3f, 5e2f}, 1e-3f}, Case{"huge", {1e5f, 3e4f, -2e5f}, 1e4f}}) {
    SCOPED_TRACE(c.name);
    Scene s = furnace(c.center + glm::vec3(0, 0, 3 * c.radius), c.center, 45);
    add_glass(s, "glass", 1.5f);
    s.spheres.push_back({.center = c.center, .radius = c.radius, .material = "glass"});
    expect_every_pixel(render(s, 16, 16, 32, no_roulette()), kEnv, 1e-4, c.name);
  }
}

TEST(hard_Refractive, BallTouchingAQuad) {
  ensure_gl_context();
  Scene s = furnace({0, 1.2f, 3}, {0, 0.6f, 0}, 50);
  s.materials.push_back({.name = "white", .color = {1, 1, 1}});
  add_glass(s, "glass", 1.5f);
  s.quads.push_back({.material = "white", .corners = {glm::vec3(-4, 0, -4), glm::vec3(-4, 0, 4),
                                                      glm::vec3(4, 0, -4), glm::vec3(4, 0, 4)}});
  s.spheres.push_back({.center = {0, 1, 0}, .radius = 1, .material = "glass"});
  expect_every_pixel(render(s, 16, 16, 32, no_roulette()), kEnv, 1e-4, "ball on a quad");
}

TEST(hard_Refractive, BallInsideABall) {
  ensure_gl_context();
  Scene s = furnace({0, 0, 3}, {0, 0, 0}, 45);
  add_glass(s, "glass", 1.5f);
  add_glass(s, "dense", 2.0f);
  s.spheres.push_back({.center = {0, 0, 0}, .radius = 1, .material = "glass"});
  s.spheres.push_back({.center = {0.2f, -0.1f, 0.1f}, .radius = 0.5f, .material = "dense"});
  expect_every_pixel(render(s, 16, 16, 32, no_roulette()), kEnv, 1e-4, "ball in a ball");
}

}  // namespace
}  // namespace glint
