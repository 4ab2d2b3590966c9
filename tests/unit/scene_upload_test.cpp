// What the scene's upload decides before any GL call: the texels a table needs and the message
// when a table cannot hold them (renderer/scene_tables.h), and where each texture's texels go
// (renderer/scene_textures.h, plan_texels).
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "renderer/scene_tables.h"
#include "renderer/scene_textures.h"
#include "renderer/shader_lib.h"

namespace glint {
namespace {

TEST(SceneTables, TexelsPerElementFollowTheLayout) {
  EXPECT_EQ(table_texels(std::vector<float>(5)), 5);
  EXPECT_EQ(table_texels(std::vector<glm::ivec4>(3)), 3);
  EXPECT_EQ(table_texels(std::vector<GpuSphere>(3)), 3 * int64_t(sizeof(GpuSphere) / 16));
  EXPECT_EQ(table_texels(std::vector<GpuQuad>(2)), 2 * int64_t(sizeof(GpuQuad) / 16));
}

TEST(SceneTables, ARefusalNamesTheTableItsSizeAndTheLimit) {
  EXPECT_NO_THROW(check_table_texels("quads", 2, 16, 16));
  try {
    check_table_texels("quads", 3, 24, 16);
    FAIL() << "not refused";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "quads (3) need 24 texels, more than this OpenGL driver holds (16 texels in a "
                           "table: GL_MAX_TEXTURE_BUFFER_SIZE)");
  }
}

std::shared_ptr<const TextureImage> texture(int width, int height, bool eight_bit) {
  auto t = std::make_shared<TextureImage>();
  t->linear.width = width;
  t->linear.height = height;
  if (eight_bit)
    t->rgba8.assign(size_t(width) * height * 4, 0);
  else
    t->linear.pixels.assign(size_t(width) * height * 4, 0.0f);
  return t;
}

// Each file's texels once in its sequence (8-bit or float), also when two layers read it; the
// records give each layer its size, first texel and format.
TEST(TexelPlan, EachImageOnceInItsSequence) {
  const auto a = texture(4, 2, true), b = texture(3, 3, false), c = texture(2, 2, true);
  const std::vector<TextureLayer> layers{
      {0, ColorEncoding::srgb}, {1, ColorEncoding::linear}, {0, ColorEncoding::linear}, {2, ColorEncoding::srgb}};
  const TexelPlan plan = plan_texels(layers, {a, b, a, c}, {"a.png", "b.exr", "a.png", "c.png"}, 1000);
  ASSERT_EQ(plan.runs[0].size(), 2u);
  ASSERT_EQ(plan.runs[1].size(), 1u);
  EXPECT_EQ(plan.texels[0], 8 + 4);
  EXPECT_EQ(plan.texels[1], 9);
  ASSERT_EQ(plan.records.size(), 4u);
  EXPECT_EQ(plan.records[0], glm::ivec4(4, 2, 0, gpu::TEXELS_8BIT_SRGB));
  EXPECT_EQ(plan.records[1], glm::ivec4(3, 3, 0, gpu::TEXELS_FLOAT));
  EXPECT_EQ(plan.records[2], glm::ivec4(4, 2, 0, gpu::TEXELS_8BIT_LINEAR)) << "a's texels again";
  EXPECT_EQ(plan.records[3], glm::ivec4(2, 2, 8, gpu::TEXELS_8BIT_SRGB));
}

TEST(TexelPlan, TheTextureThatOverflowsIsNamed) {
  const auto a = texture(4, 4, true), b = texture(4, 4, true), f = texture(8, 8, false);
  EXPECT_NO_THROW(plan_texels({{0}, {1}, {2}}, {a, b, f}, {"a.png", "b.png", "f.exr"}, 64));
  try {
    plan_texels({{0}, {1}}, {a, b}, {"a.png", "b.png"}, 31);
    FAIL() << "not refused";
  } catch (const ImageError& e) {
    EXPECT_STREQ(e.what(), "textures[1].path: b.png: the textures need 32 8-bit texels, more than this "
                           "OpenGL driver holds (31 texels: 16384 per row, GL_MAX_TEXTURE_SIZE rows)");
  }
}

}  // namespace
}  // namespace glint
