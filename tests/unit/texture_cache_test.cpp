// Textures as the renderer keeps them (renderer/image.h TextureImage): 8-bit files stay 8-bit
// and the shader's per-tap sRGB decode gives the loader's values; each file is decoded once
// (renderer/texture_cache.h), however many paths name it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <stb_image_write.h>

#include "renderer/image.h"
#include "renderer/project_file.h"
#include "renderer/shader_lib.h"
#include "renderer/texture_cache.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

using test::TempDir;

TEST(TextureImage, EightBitFilesStayEightBitWithTheLoadersValues) {
  TempDir dir;
  const unsigned char rgba[] = {0, 255, 188, 188, 188, 0, 255, 64, 1, 2, 3, 4,
                                250, 128, 17, 255, 9, 99, 199, 0, 40, 41, 42, 43};
  ASSERT_TRUE(stbi_write_png((dir / "a.png").string().c_str(), 3, 2, 4, rgba, 12));
  const TextureImage texture = load_texture_image(dir / "a.png");
  ASSERT_TRUE(texture.eight_bit());
  ASSERT_EQ(texture.width(), 3);
  ASSERT_EQ(texture.height(), 2);
  EXPECT_EQ(texture.byte_size(), 24u);  // 4 bytes a texel, not 16
  EXPECT_EQ(texture.rgba8, std::vector<unsigned char>(rgba, rgba + 24));
  for (ColorEncoding encoding : {ColorEncoding::srgb, ColorEncoding::linear}) {
    const Image loaded = load_image(dir / "a.png", encoding);
    const Image converted = to_linear_image(texture, encoding);
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 3; ++x)
        for (int c = 0; c < 4; ++c) {
          EXPECT_EQ(texture.value(x, y, c, encoding), loaded.at(x, y)[c]) << x << " " << y << " " << c;
          EXPECT_EQ(converted.at(x, y)[c], loaded.at(x, y)[c]);
        }
  }
  // Grey becomes (g, g, g) with opaque alpha.
  const unsigned char grey[] = {7, 200};
  ASSERT_TRUE(stbi_write_png((dir / "g.png").string().c_str(), 2, 1, 1, grey, 2));
  EXPECT_EQ(load_texture_image(dir / "g.png").rgba8,
            (std::vector<unsigned char>{7, 7, 7, 255, 200, 200, 200, 255}));
  // Float files are the loader's linear floats.
  Image hdr{2, 1, {0.5f, 2.0f, 30.0f, 1.0f, 0.0f, 0.25f, 1e4f, 0.5f}};
  save_image(dir / "f.exr", hdr);
  const TextureImage exr = load_texture_image(dir / "f.exr");
  EXPECT_FALSE(exr.eight_bit());
  EXPECT_EQ(exr.linear.pixels, hdr.pixels);
}

// The shader decodes each 8-bit tap (shaders/lib/mapping.glsl) where the loader used a table of
// srgb_to_linear: the same value to within rounding for every byte.
TEST(TextureImage, ShaderSrgbDecodeMatchesTheLoader) {
  TempDir dir;
  unsigned char all[256 * 3];
  for (int i = 0; i < 256; ++i) all[i * 3] = all[i * 3 + 1] = all[i * 3 + 2] = static_cast<unsigned char>(i);
  ASSERT_TRUE(stbi_write_png((dir / "all.png").string().c_str(), 256, 1, 3, all, 256 * 3));
  const Image loaded = load_image(dir / "all.png", ColorEncoding::srgb);
  for (int i = 0; i < 256; ++i) {
    const float shader = gpu::srgb_decode(static_cast<float>(i) / 255.0f);
    EXPECT_NEAR(shader, loaded.at(i, 0)[0], 2e-7f * loaded.at(i, 0)[0]) << i;
  }
}

TEST(TextureCache, EachFileIsDecodedOnce) {
  TempDir dir;
  save_image(dir / "a.png", Image{2, 1, {0.1f, 0.2f, 0.3f, 1, 0.4f, 0.5f, 0.6f, 1}});
  fs::create_directories(dir / "sub");
  fs::create_symlink(dir / "a.png", dir / "link.png");
  std::ofstream(dir / "p.glint") << R"({"format": "glint-project", "version": 1,
    "textures": [{"name": "a", "path": "a.png"}, {"name": "b", "path": "./a.png"},
                 {"name": "c", "path": "sub/../a.png"}, {"name": "d", "path": "link.png"}],
    "materials": [{"name": "m", "color_texture": "a", "emission_texture": "b",
                   "roughness_texture": "c"}, {"name": "n", "color_texture": "d"}],
    "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "m"}]})";
  const size_t before = texture_cache_stats().decodes;
  const Scene scene = load_project(dir / "p.glint");
  EXPECT_EQ(texture_cache_stats().decodes, before + 1);  // four names, one file
  // What the renderer uploads is that same decoded image.
  EXPECT_EQ(load_texture_cached(resolve_asset_path(scene, "link.png")),
            load_texture_cached(resolve_asset_path(scene, "sub/../a.png")));
  load_project(dir / "p.glint");
  EXPECT_EQ(texture_cache_stats().decodes, before + 1);
  // A changed file is decoded again.
  save_image(dir / "a.png", Image{1, 1, {0.9f, 0.9f, 0.9f, 1}});
  load_project(dir / "p.glint");
  EXPECT_EQ(texture_cache_stats().decodes, before + 2);
  EXPECT_EQ(load_texture_cached(dir / "a.png")->width(), 1);
}

}  // namespace
}  // namespace glint
