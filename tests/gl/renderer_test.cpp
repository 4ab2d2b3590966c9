// GL tests of the progressive renderer on small images (run serially; llvmpipe in CI).
#include <cstdio>
#include <stdexcept>

#include <epoxy/gl.h>

#include "renderer/shader_lib.h"
#include "tests/gl/gl_test_support.h"

namespace glint {
namespace {

using test::channel_stats;
using test::empty_scene;
using test::ensure_gl_context;

// (a) White furnace: a white Lambertian sphere under a constant environment L reflects exactly
// L in every direction, so every pixel equals L. Each path (cosine sampling, weight = albedo = 1,
// then escape: a sphere is convex) carries exactly L, so the estimator has zero variance and the
// tolerance is float rounding of the running mean, not noise.
TEST(GlRenderer, WhiteFurnaceRendersTheEnvironmentEverywhere) {
  ensure_gl_context();
  Scene scene = empty_scene();
  scene.environment.color = {0.25f, 0.5f, 1.0f};
  scene.environment.intensity = 2.0f;  // L = (0.5, 1, 2)
  scene.materials.push_back({.name = "white", .color = {1, 1, 1}});
  scene.spheres.push_back({.name = "ball", .center = {0, 0, 0}, .radius = 1.5f, .material = "white"});
  GpuRenderer r;
  r.sync(scene, 48, 32);
  r.trace(16);
  Image img = r.read_accumulation();
  const float expected[3] = {0.5f, 1.0f, 2.0f};
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(img.at(x, y)[c], expected[c], 1e-5f * expected[c]) << x << "," << y;
}

// (b) An emissive quad filling the middle of the view renders its emission. Interior pixels
// see only the quad (zero variance); edge pixels mix quad and black background.
TEST(GlRenderer, EmissiveQuadSeenDirectlyRendersItsEmission) {
  ensure_gl_context();
  Scene scene = empty_scene();
  scene.materials.push_back({.name = "lamp", .color = {0, 0, 0}, .emission = {3, 2, 0.5f}});
  scene.quads.push_back({.name = "panel", .material = "lamp",
                         .corners = {glm::vec3{-1, -1, 0}, glm::vec3{-1, 1, 0}, glm::vec3{1, -1, 0}, glm::vec3{1, 1, 0}}});
  GpuRenderer r;
  r.sync(scene, 64, 64);
  r.trace(8);
  Image img = r.read_accumulation();
  // The quad spans +-1 at distance 5 with vfov 40 deg: half-height 1/(5 tan 20deg) = 0.55 of
  // the half-image; the central 40% of the image is well inside it.
  for (int y = 20; y < 44; ++y)
    for (int x = 20; x < 44; ++x) {
      ASSERT_NEAR(img.at(x, y)[0], 3.0f, 1e-5f);
      ASSERT_NEAR(img.at(x, y)[1], 2.0f, 1e-5f);
      ASSERT_NEAR(img.at(x, y)[2], 0.5f, 1e-5f);
    }
  EXPECT_EQ(img.at(1, 1)[0], 0.0f);  // the corner sees the black environment
}

// The scene's tables are integer buffer textures: a scene whose quads need more texels than a
// table holds (GL_MAX_TEXTURE_BUFFER_SIZE; here an option's 100, 8 texels a quad) is refused
// with the count and the limit, and the renderer keeps the previous scene.
TEST(GlRenderer, ShapesBeyondTheTablesLimitAreRefused) {
  ensure_gl_context();
  Scene scene = empty_scene();
  scene.materials.push_back({.name = "lamp", .color = {0, 0, 0}, .emission = {3, 2, 0.5f}});
  const Quad panel{.name = "panel", .material = "lamp",
                   .corners = {glm::vec3{-1, -1, 0}, glm::vec3{-1, 1, 0}, glm::vec3{1, -1, 0}, glm::vec3{1, 1, 0}}};
  scene.quads.assign(12, panel);  // 96 texels
  GpuRendererOptions options;
  options.max_table_texels = 100;
  GpuRenderer r(options);
  r.sync(scene, 8, 8);
  Scene large = scene;
  large.quads.push_back(panel);  // 104 texels
  large.materials[0].emission = {1, 1, 1};
  try {
    r.sync(large, 8, 8);
    ADD_FAILURE() << "13 quads (104 texels) were accepted with a limit of 100 texels";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              "quads (13) need 104 texels, more than this OpenGL driver holds (100 texels in a "
              "table: GL_MAX_TEXTURE_BUFFER_SIZE)");
  }
  r.trace(1);
  EXPECT_NEAR(r.read_accumulation().at(4, 4)[0], 3.0f, 1e-5);  // the previous scene's emission
}

Scene noisy_scene() {
  Scene scene = empty_scene();
  scene.environment.color = {0.8f, 0.9f, 1.0f};
  scene.materials.push_back({.name = "floor", .color = {0.7f, 0.6f, 0.5f}});
  scene.materials.push_back({.name = "gloss", .type = MaterialType::glossy, .color = {0.2f, 0.4f, 0.8f}, .roughness = 0.3f});
  scene.spheres.push_back({.name = "ball", .center = {0, 0, 0}, .radius = 1.0f, .material = "gloss"});
  scene.quads.push_back({.name = "ground", .material = "floor",
                         .corners = {glm::vec3{-5, -1, -5}, glm::vec3{-5, -1, 5}, glm::vec3{5, -1, -5}, glm::vec3{5, -1, 5}}});
  return scene;
}

// (c) Samples are indexed by their global number, so N passes of 1 sample and one pass of N
// samples draw exactly the same paths: the two means agree to float rounding of the running
// mean. A different seed draws independent paths: the image-mean difference must then be
// within 4 standard errors estimated from the per-pixel differences.
TEST(GlRenderer, ManyOneSamplePassesEqualOneManySamplePass) {
  ensure_gl_context();
  const int n = 16;
  Scene scene = noisy_scene();
  GpuRenderer a, b;
  a.sync(scene, 32, 32);
  b.sync(scene, 32, 32);
  for (int i = 0; i < n; ++i) a.trace(1);
  b.trace(n);
  EXPECT_EQ(a.sample_count(), n);
  EXPECT_EQ(b.sample_count(), n);
  Image ia = a.read_accumulation(), ib = b.read_accumulation();
  for (size_t i = 0; i < ia.pixels.size(); ++i)
    ASSERT_NEAR(ia.pixels[i], ib.pixels[i], 1e-5f * (1.0f + std::abs(ib.pixels[i])));

  scene.render.seed = 7;
  GpuRenderer c;
  c.sync(scene, 32, 32);
  c.trace(n);
  Image ic = c.read_accumulation();
  double sum = 0, sum2 = 0, differing = 0;
  const size_t pixels = static_cast<size_t>(ic.width) * ic.height;
  for (size_t p = 0; p < pixels; ++p) {
    double d = ia.pixels[p * 4 + 1] - ic.pixels[p * 4 + 1];
    sum += d;
    sum2 += d * d;
    differing += d != 0;
  }
  double mean = sum / pixels;
  double standard_error = std::sqrt((sum2 / pixels - mean * mean) / (pixels - 1));
  EXPECT_GT(differing, pixels / 2) << "another seed must draw other samples";
  EXPECT_LT(std::abs(mean), 4 * standard_error);
}

// (d) Exposure re-runs only the tonemap: the sample count and the accumulation stay
// bit-identical, and the display equals the tonemap formula (shared with the shader) applied
// to the accumulation, to the 8-bit display precision.
TEST(GlRenderer, ExposureChangesOnlyTheDisplay) {
  ensure_gl_context();
  Scene scene = noisy_scene();
  GpuRenderer r;
  r.sync(scene, 32, 32);
  r.trace(4);
  Image before = r.read_accumulation();
  Image display_before = r.read_display();
  for (float exposure : {1.5f, -2.0f}) {
    for (Tonemap tonemap : {Tonemap::filmic, Tonemap::linear}) {
      scene.display.exposure = exposure;
      scene.display.tonemap = tonemap;
      SyncResult sync = r.sync(scene, 32, 32);
      EXPECT_FALSE(sync.accumulation_reset);
      EXPECT_TRUE(sync.display_changed);
      EXPECT_EQ(r.sample_count(), 4);
      Image after = r.read_accumulation();
      ASSERT_EQ(after.pixels, before.pixels);
      Image display = r.read_display();
      int mode = tonemap == Tonemap::filmic ? gpu::TONEMAP_FILMIC : gpu::TONEMAP_LINEAR;
      for (size_t i = 0; i < display.pixels.size(); i += 4)
        for (int c = 0; c < 3; ++c)
          ASSERT_NEAR(display.pixels[i + c], gpu::tonemap_channel(after.pixels[i + c], exposure, mode),
                      0.5f / 255.0f + 1e-4f);
      EXPECT_NE(display.pixels, display_before.pixels);
    }
  }
  // Any radiance edit resets.
  scene.spheres[0].radius = 0.9f;
  EXPECT_TRUE(r.sync(scene, 32, 32).accumulation_reset);
  EXPECT_EQ(r.sample_count(), 0);
}

// (e) Thin lens: a small emitter at the focus distance stays a sharp dot while one far behind
// it spreads into a disc. Spread = luminance-weighted RMS radius in pixels around the centroid.
double spot_radius(const Image& img, int x0, int x1) {
  double w = 0, sx = 0, sy = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = x0; x < x1; ++x) {
      double v = img.at(x, y)[0];
      w += v;
      sx += v * x;
      sy += v * y;
    }
  double cx = sx / w, cy = sy / w, r2 = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = x0; x < x1; ++x) {
      double v = img.at(x, y)[0];
      r2 += v * ((x - cx) * (x - cx) + (y - cy) * (y - cy));
    }
  return std::sqrt(r2 / w);
}

TEST(GlRenderer, ThinLensKeepsTheFocusPlaneSharpAndBlursTheBackground) {
  ensure_gl_context();
  Scene scene = empty_scene();
  scene.camera.focus_distance = 5;
  scene.camera.vfov_deg = 30;
  scene.materials.push_back({.name = "lamp", .color = {0, 0, 0}, .emission = {100, 100, 100}});
  // Left emitter on the focus plane (z = 0); right one 20 units further (z = -20), scaled to
  // cover a similar angle.
  scene.spheres.push_back({.name = "near", .center = {-0.6f, 0, 0}, .radius = 0.05f, .material = "lamp"});
  scene.spheres.push_back({.name = "far", .center = {3.0f, 0, -20}, .radius = 0.25f, .material = "lamp"});
  const int w = 96, h = 48;
  GpuRenderer r;
  scene.camera.aperture_radius = 0;
  r.sync(scene, w, h);
  r.trace(64);
  Image pinhole = r.read_accumulation();
  scene.camera.aperture_radius = 0.2f;
  r.sync(scene, w, h);
  r.trace(256);
  Image lens = r.read_accumulation();
  double near_pin = spot_radius(pinhole, 0, w / 2), near_lens = spot_radius(lens, 0, w / 2);
  double far_pin = spot_radius(pinhole, w / 2, w), far_lens = spot_radius(lens, w / 2, w);
  // Circle of confusion of the far emitter (distance D = 25 along the view, focus F = 5):
  // radius A |1 - F/D| / (F tan(vfov/2)) image half-heights = 2.87 px. A uniform disc of radius
  // R has RMS radius R / sqrt(2); it adds in quadrature to the pinhole spot's own spread.
  const double coc = 0.2 * (1.0 - 5.0 / 25.0) / (5.0 * std::tan(glm::radians(15.0))) * (h / 2);
  const double predicted = std::sqrt(far_pin * far_pin + coc * coc / 2);
  EXPECT_LT(near_lens, near_pin * 1.1 + 0.05) << "in-focus spot must stay sharp";
  EXPECT_NEAR(far_lens, predicted, 0.1 * predicted) << "out-of-focus spot must blur by the thin-lens amount";
}

}  // namespace
}  // namespace glint
