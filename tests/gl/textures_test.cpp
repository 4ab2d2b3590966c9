// Textures of different sizes in one texture array, and coverage from colour alpha.
#include <unistd.h>

#include <filesystem>

#include "tests/gl/gl_test_support.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

Image solid_rows(int width, int height, std::vector<glm::vec4> texels) {
  Image img;
  img.width = width;
  img.height = height;
  for (const glm::vec4& t : texels) img.pixels.insert(img.pixels.end(), {t.r, t.g, t.b, t.a});
  return img;
}

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("glint-gl-textures-" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

Quad facing_quad(const std::string& material, float x0, float x1, float half_height = 1) {
  const float y0 = -half_height, y1 = half_height;
  return {.name = material, .material = material,
          .corners = {glm::vec3{x0, y0, 0}, glm::vec3{x0, y1, 0}, glm::vec3{x1, y0, 0}, glm::vec3{x1, y1, 0}}};
}

// The pixel where world point (x, y, 0) appears for the camera of empty_scene().
glm::ivec2 pixel_of(float x, float y, int w, int h, const Scene& s) {
  float half_h = 5.0f * std::tan(glm::radians(s.camera.vfov_deg) * 0.5f);
  float half_w = half_h * float(w) / float(h);
  return {int((0.5f + 0.5f * x / half_w) * w), int((0.5f - 0.5f * y / half_h) * h)};
}

TEST(GlTextures, TexturesOfDifferentSizesShareTheArray) {
  test::ensure_gl_context();
  TempDir dir;
  // EXR keeps float texels exactly (no sRGB decode): 2x1 red|green and 1x2 blue/yellow.
  save_image(dir.path / "a.exr", solid_rows(2, 1, {{1, 0, 0, 1}, {0, 1, 0, 1}}));
  save_image(dir.path / "b.exr", solid_rows(1, 2, {{0, 0, 1, 1}, {1, 1, 0, 1}}));
  Scene scene = test::empty_scene();
  scene.base_dir = dir.path;
  scene.render.max_bounces = 0;
  scene.textures = {{.name = "a", .path = "a.exr"}, {.name = "b", .path = "b.exr"}};
  scene.materials.push_back({.name = "ta", .color = {0, 0, 0}, .emission = {1, 1, 1}, .emission_texture = "a"});
  scene.materials.push_back({.name = "tb", .color = {0, 0, 0}, .emission = {1, 1, 1}, .emission_texture = "b"});
  scene.quads = {facing_quad("ta", -2.2f, -0.2f), facing_quad("tb", 0.2f, 2.2f)};
  const int w = 128, h = 64;
  GpuRenderer r;
  r.sync(scene, w, h);
  r.trace(16);
  Image img = r.read_accumulation();
  // Texel centres: u = 0.25 and 0.75 across quad a; v = 0.25 (first row) and 0.75 across b.
  // uv (0,0) is corner p0 = (x0, -1), v grows with y. The pixel footprint mixes a few percent
  // of the neighbouring texel through the bilinear filter.
  auto at = [&](float x, float y) {
    glm::ivec2 p = pixel_of(x, y, w, h, scene);
    const float* v = img.at(p.x, p.y);
    return glm::vec3(v[0], v[1], v[2]);
  };
  glm::vec3 red = at(-1.7f, 0), green = at(-0.7f, 0), blue = at(1.2f, -0.5f), yellow = at(1.2f, 0.5f);
  EXPECT_GT(red.r, 0.9f); EXPECT_LT(red.g, 0.1f);
  EXPECT_GT(green.g, 0.9f); EXPECT_LT(green.r, 0.1f);
  EXPECT_GT(blue.b, 0.9f); EXPECT_LT(blue.r, 0.1f);
  EXPECT_GT(yellow.r, 0.9f); EXPECT_GT(yellow.g, 0.9f); EXPECT_LT(yellow.b, 0.1f);

  // Reassigning a slot changes the layers in use: the left quad now shows texture b.
  scene.materials[0].emission_texture = "b";
  EXPECT_TRUE(r.sync(scene, w, h).accumulation_reset);
  r.trace(16);
  img = r.read_accumulation();
  glm::vec3 left_low = at(-1.7f, -0.5f), left_high = at(-1.7f, 0.5f);
  EXPECT_GT(left_low.b, 0.9f); EXPECT_LT(left_low.r, 0.1f);
  EXPECT_GT(left_high.r, 0.9f); EXPECT_GT(left_high.g, 0.9f);
}

// A black surface of coverage c in front of an emitter E: each sample sees E with probability
// 1 - c, so a pixel's mean is (1 - c) E with standard deviation E sqrt(c (1 - c) / N).
TEST(GlTextures, ColourAlphaTimesOpacityIsTheCoverage) {
  test::ensure_gl_context();
  TempDir dir;
  save_image(dir.path / "half.exr", solid_rows(1, 1, {{0, 0, 0, 0.5f}}));
  Scene scene = test::empty_scene();
  scene.base_dir = dir.path;
  scene.textures = {{.name = "half", .path = "half.exr"}};
  scene.materials.push_back({.name = "veil", .color = {1, 1, 1}, .color_texture = "half", .opacity = 0.5f});
  scene.materials.push_back({.name = "lamp", .color = {0, 0, 0}, .emission = {2, 2, 2}});
  // Both quads fill the whole view.
  Quad veil = facing_quad("veil", -3, 3, 3);
  for (auto& c : veil.corners) c.z = 1;
  scene.quads = {veil, facing_quad("lamp", -3, 3, 3)};
  scene.render.max_bounces = 0;  // what the veil reflects is not counted: only pass-through
  const int w = 32, h = 32, n = 64;
  GpuRenderer r;
  r.sync(scene, w, h);
  r.trace(n);
  Image img = r.read_accumulation();
  const double c = 0.25, e = 2.0;  // alpha 0.5 x opacity 0.5
  test::Stats s = test::channel_stats(img, 0, [](int, int) { return true; });
  double sigma = e * std::sqrt(c * (1 - c) / (double(n) * s.count));
  EXPECT_NEAR(s.mean, (1 - c) * e, 4 * sigma);
}

}  // namespace
}  // namespace glint
