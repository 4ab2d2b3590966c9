// The auxiliary images of renderer/aov_pass.h: albedo and normal at the first surface that is
// not a perfect specular one, through mirrors and smooth thin glass; and the colour image is
// the same with them on. The tolerances are float32 rounding of a sum of a few equal terms
// (n additions round by at most n * 2^-24 relative; 1e-5 covers n = 16 with room).
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/gpu_renderer.h"
#include "tests/gl/gl_test_support.h"

namespace glint {
namespace {

constexpr double kRounding = 1e-5;

Quad square(const std::string& material, float z, float half) {
  Quad q;
  q.material = material;
  q.corners = {glm::vec3(-half, -half, z), glm::vec3(-half, half, z), glm::vec3(half, -half, z),
               glm::vec3(half, half, z)};
  return q;
}

Material material(const std::string& name, MaterialType type, glm::vec3 color) {
  Material m;
  m.name = name;
  m.type = type;
  m.color = color;
  m.roughness = 0;
  return m;
}

AovImages render_aovs(const Scene& scene, int spp, int size = 16) {
  test::ensure_gl_context();
  GpuRenderer renderer;
  renderer.set_aovs_enabled(true);
  renderer.sync(scene, size, size);
  renderer.trace(spp);
  return renderer.read_aovs();
}

void expect_everywhere(const Image& image, glm::vec3 expected, const char* what) {
  int wrong = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c)
        if (std::abs(image.at(x, y)[c] - expected[c]) > kRounding * std::max(1.0f, std::abs(expected[c]))) {
          if (++wrong <= 3)
            ADD_FAILURE() << what << " at (" << x << ", " << y << ") channel " << c << ": "
                          << image.at(x, y)[c] << ", expected " << expected[c];
        }
  EXPECT_EQ(wrong, 0) << what;
}

TEST(Aov, MattePlaneAlbedoIsItsColourAndItsNormalFacesTheCamera) {
  Scene s = test::empty_scene();
  s.materials = {material("paint", MaterialType::matte, {0.2f, 0.5f, 0.8f})};
  s.quads = {square("paint", 0, 100)};
  const AovImages aovs = render_aovs(s, 8);
  expect_everywhere(aovs.albedo, {0.2f, 0.5f, 0.8f}, "albedo");
  expect_everywhere(aovs.normal, {0, 0, 1}, "normal");
}

TEST(Aov, NormalsOfASphereAreUnitLengthAndTheBackgroundHasNone) {
  Scene s = test::empty_scene();
  s.materials = {material("paint", MaterialType::matte, {0.5f, 0.5f, 0.5f})};
  Sphere ball;
  ball.radius = 1;
  ball.material = "paint";
  s.spheres = {ball};
  // One sample per pixel: each pixel holds one normal, of length 1 exactly on the sphere (a
  // mean of several directions would be shorter) and 0 where the ray escaped.
  const AovImages aovs = render_aovs(s, 1, 32);
  int on_sphere = 0, background = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const float* n = aovs.normal.at(x, y);
      const double length = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
      if (length == 0) {
        ++background;
        EXPECT_EQ(aovs.albedo.at(x, y)[0], 1.0f) << "the background's albedo is 1";
        continue;
      }
      ++on_sphere;
      EXPECT_NEAR(length, 1.0, kRounding) << "(" << x << ", " << y << ")";
      EXPECT_GT(n[2], 0.0f) << "the normal faces the camera (+z)";
    }
  EXPECT_GT(on_sphere, 20);
  EXPECT_GT(background, 20);
}

TEST(Aov, AMirrorShowsTheAlbedoAndNormalOfWhatItReflects) {
  Scene s = test::empty_scene();  // camera at z = 5 looking down -z
  s.materials = {material("mirror", MaterialType::reflective, {1, 1, 1}),
                 material("wall", MaterialType::matte, {0.7f, 0.3f, 0.1f})};
  // The mirror fills the view; the wall behind the camera is what it shows.
  s.quads = {square("mirror", 0, 100), square("wall", 10, 1000)};
  const AovImages aovs = render_aovs(s, 4);
  expect_everywhere(aovs.albedo, {0.7f, 0.3f, 0.1f}, "albedo");
  expect_everywhere(aovs.normal, {0, 0, -1}, "normal");  // the wall's, facing the mirror
}

TEST(Aov, SmoothThinGlassPassesStraightThroughWithItsTint) {
  Scene s = test::empty_scene();
  s.materials = {material("glass", MaterialType::transparent, {0.5f, 1.0f, 0.8f}),
                 material("wall", MaterialType::matte, {0.6f, 0.4f, 0.2f})};
  s.quads = {square("glass", 1, 100), square("wall", 0, 100)};
  const AovImages aovs = render_aovs(s, 4);
  expect_everywhere(aovs.albedo, {0.5f * 0.6f, 1.0f * 0.4f, 0.8f * 0.2f}, "albedo");
  expect_everywhere(aovs.normal, {0, 0, 1}, "normal");
}

TEST(Aov, TheColourImageIsTheSameWithAovsOn) {
  test::ensure_gl_context();
  Scene s = test::empty_scene();
  s.environment.color = {0.8f, 0.9f, 1.0f};
  s.materials = {material("paint", MaterialType::matte, {0.6f, 0.4f, 0.2f})};
  Sphere ball;
  ball.material = "paint";
  s.spheres = {ball};
  s.quads = {square("paint", -1, 100)};
  for (const TraceBackend backend : {TraceBackend::fragment, TraceBackend::compute}) {
    Image colour[2];
    for (int on = 0; on < 2; ++on) {
      GpuRendererOptions options;
      options.backend = backend;
      GpuRenderer renderer(options);
      renderer.set_aovs_enabled(on == 1);
      renderer.sync(s, 16, 16);
      renderer.trace(3);
      renderer.trace(2);
      colour[on] = renderer.read_accumulation();
    }
    EXPECT_EQ(colour[0].pixels, colour[1].pixels) << backend_name(backend);
  }
}

TEST(Aov, AResetClearsThem) {
  test::ensure_gl_context();
  Scene s = test::empty_scene();
  s.materials = {material("paint", MaterialType::matte, {0.2f, 0.5f, 0.8f})};
  s.quads = {square("paint", 0, 100)};
  GpuRenderer renderer;
  renderer.set_aovs_enabled(true);
  renderer.sync(s, 8, 8);
  renderer.trace(4);
  s.materials[0].color = {0.9f, 0.1f, 0.3f};
  EXPECT_TRUE(renderer.sync(s, 8, 8).accumulation_reset);
  renderer.trace(2);
  expect_everywhere(renderer.read_aovs().albedo, {0.9f, 0.1f, 0.3f}, "albedo after the reset");
}

}  // namespace
}  // namespace glint
