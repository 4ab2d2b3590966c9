// Textures of different sizes, many textures, 8-bit texels, the driver's limit, and coverage
// from colour alpha.
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

TEST(GlTextures, TexturesOfDifferentSizesShareTheTexelBuffer) {
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

// Texture memory follows each texture's own size: a 16384x1 and a 1x16384 texture once made
// one 16384x16384 array of two layers (8 GiB), whose allocation failed and left every textured
// surface black.
TEST(GlTextures, LongThinTexturesTakeTheirOwnSize) {
  test::ensure_gl_context();
  TempDir dir;
  save_image(dir.path / "row.png", solid_rows(16384, 1, std::vector<glm::vec4>(16384, {1, 0, 0, 1})));
  save_image(dir.path / "column.png", solid_rows(1, 16384, std::vector<glm::vec4>(16384, {0, 1, 0, 1})));
  Scene scene = test::empty_scene();
  scene.base_dir = dir.path;
  scene.render.max_bounces = 0;
  scene.textures = {{.name = "row", .path = "row.png"}, {.name = "column", .path = "column.png"}};
  scene.materials.push_back({.name = "r", .color = {0, 0, 0}, .emission = {1, 1, 1}, .emission_texture = "row"});
  scene.materials.push_back({.name = "c", .color = {0, 0, 0}, .emission = {1, 1, 1}, .emission_texture = "column"});
  scene.quads = {facing_quad("r", -2.2f, -0.2f), facing_quad("c", 0.2f, 2.2f)};
  const int w = 64, h = 32;
  GpuRenderer r;
  r.sync(scene, w, h);
  r.trace(1);
  const Image img = r.read_accumulation();
  const glm::ivec2 left = pixel_of(-1.2f, 0, w, h, scene), right = pixel_of(1.2f, 0, w, h, scene);
  EXPECT_NEAR(img.at(left.x, left.y)[0], 1.0f, 1e-5);
  EXPECT_NEAR(img.at(left.x, left.y)[1], 0.0f, 1e-5);
  EXPECT_NEAR(img.at(right.x, right.y)[0], 0.0f, 1e-5);
  EXPECT_NEAR(img.at(right.x, right.y)[1], 1.0f, 1e-5);
}

// More textures than a texture array has layers (2048 on llvmpipe, GL_MAX_ARRAY_TEXTURE_LAYERS):
// 2100 texture entries, each its own layer, all naming one file (decoded once).
TEST(GlTextures, MoreTexturesThanAnArrayHasLayers) {
  test::ensure_gl_context();
  TempDir dir;
  save_image(dir.path / "grey.png", solid_rows(1, 1, {{0.5f, 0.5f, 0.5f, 1}}));
  Scene scene = test::empty_scene();
  scene.base_dir = dir.path;
  scene.render.max_bounces = 0;
  const int count = 2100;
  for (int i = 0; i < count; ++i) {
    const std::string n = std::to_string(i);
    scene.textures.push_back({.name = "t" + n, .path = "grey.png"});
    scene.materials.push_back({.name = "m" + n, .color = {0, 0, 0}, .emission = {1, 1, 1}, .emission_texture = "t" + n});
    Quad q = facing_quad("m" + n, -3, 3, 3);
    for (auto& c : q.corners) c.z = 0.001f * float(i);  // the last is the nearest
    scene.quads.push_back(q);
  }
  GpuRenderer r;
  r.sync(scene, 4, 4);
  r.trace(1);
  const Image img = r.read_accumulation();
  const float expected = load_image(dir.path / "grey.png", ColorEncoding::srgb).at(0, 0)[0];
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_NEAR(img.at(x, y)[1], expected, 1e-5f * expected) << x << " " << y;
}

// 8-bit textures stay 8-bit on the GPU and the shader decodes sRGB per tap: the same radiance
// as the load-time decode (load_image) to within rounding, for dark, middle and bright bytes.
TEST(GlTextures, EightBitTexelsGiveTheLoadersValues) {
  test::ensure_gl_context();
  TempDir dir;
  Scene scene = test::empty_scene();
  scene.base_dir = dir.path;
  scene.render.max_bounces = 0;
  const std::vector<int> bytes = {0, 1, 10, 50, 128, 200, 254, 255};
  for (size_t i = 0; i < bytes.size(); ++i) {
    const std::string n = std::to_string(i);
    const float v = float(bytes[i]) / 255.0f;  // written back as exactly this byte
    save_image(dir.path / (n + ".png"), solid_rows(1, 1, {{v, v, v, 1}}));
    scene.textures.push_back({.name = n, .path = n + ".png"});
    scene.materials.push_back({.name = n, .color = {0, 0, 0}, .emission = {1, 1, 1}, .emission_texture = n});
    const float x0 = -8.0f + 2.0f * float(i);
    scene.quads.push_back(facing_quad(n, x0 + 0.1f, x0 + 1.9f));
  }
  const int w = 256, h = 32;
  GpuRenderer r;
  r.sync(scene, w, h);
  r.trace(1);
  const Image img = r.read_accumulation();
  for (size_t i = 0; i < bytes.size(); ++i) {
    const float expected = load_image(dir.path / (std::to_string(i) + ".png"), ColorEncoding::srgb).at(0, 0)[0];
    const glm::ivec2 p = pixel_of(-7.0f + 2.0f * float(i), 0, w, h, scene);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(img.at(p.x, p.y)[c], expected, 1e-5f * expected + 1e-7f) << "byte " << bytes[i];
  }
}

// What the driver cannot hold is refused with the limit, naming the texture; the renderer keeps
// its previous state and renders a scene within the limit.
TEST(GlTextures, TexturesBeyondTheDriversLimitAreRefused) {
  test::ensure_gl_context();
  TempDir dir;
  save_image(dir.path / "small.png", solid_rows(8, 8, std::vector<glm::vec4>(64, {1, 1, 1, 1})));
  save_image(dir.path / "large.png", solid_rows(16, 16, std::vector<glm::vec4>(256, {1, 1, 1, 1})));
  Scene scene = test::empty_scene();
  scene.base_dir = dir.path;
  scene.render.max_bounces = 0;
  scene.textures = {{.name = "t", .path = "small.png"}};
  scene.materials.push_back({.name = "m", .color = {0, 0, 0}, .emission = {1, 1, 1}, .emission_texture = "t"});
  scene.quads = {facing_quad("m", -3, 3, 3)};
  GpuRendererOptions options;
  options.max_texture_texels = 100;
  GpuRenderer r(options);
  r.sync(scene, 4, 4);
  Scene large = scene;
  large.textures[0].path = "large.png";
  try {
    r.sync(large, 4, 4);
    ADD_FAILURE() << "a texture of 256 texels was accepted with a limit of 100";
  } catch (const ImageError& e) {
    EXPECT_EQ(std::string(e.what()),
              "textures[0].path: " + (dir.path / "large.png").string() +
                  ": the textures need 256 8-bit texels, more than this OpenGL driver holds (100 "
                  "texels: 16384 per row, GL_MAX_TEXTURE_SIZE rows)");
  }
  r.sync(scene, 4, 4);
  r.trace(1);
  EXPECT_NEAR(r.read_accumulation().at(1, 1)[0], 1.0f, 1e-5);
}

}  // namespace
}  // namespace glint
