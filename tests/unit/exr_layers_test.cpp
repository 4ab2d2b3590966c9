// Multi-layer OpenEXR files (save_exr_layers, load_exr_layer in renderer/image.h): the
// denoised output with its noisy colour, albedo and normal layers.
#include <gtest/gtest.h>

#include "renderer/image.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

Image ramp(int w, int h, float offset) {
  Image image = Image::filled(w, h, 0.0f);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = offset + 0.01f * static_cast<float>(i);
  return image;
}

TEST(ExrLayers, EveryLayerReadsBackExactly) {
  test::TempDir dir;
  const auto file = dir.path() / "layers.exr";
  const Image colour = ramp(20, 17, 0), noisy = ramp(20, 17, 1), albedo = ramp(20, 17, 2), normal = ramp(20, 17, -3);
  save_exr_layers(file, {{"", &colour, "RGBA"}, {"noisy", &noisy, "RGBA"}, {"albedo", &albedo, "RGB"},
                         {"N", &normal, "XYZ"}});
  // The unnamed layer is what any reader (and load_image) sees as the image.
  EXPECT_EQ(load_image(file, ColorEncoding::linear).pixels, colour.pixels);
  EXPECT_EQ(load_exr_layer(file, "noisy").pixels, noisy.pixels);
  for (const auto& [name, image] : {std::pair{"albedo", &albedo}, std::pair{"N", &normal}}) {
    const Image read = load_exr_layer(file, name);
    ASSERT_EQ(read.pixels.size(), image->pixels.size());
    for (size_t i = 0; i < read.pixels.size(); ++i)
      EXPECT_EQ(read.pixels[i], i % 4 == 3 ? 1.0f : image->pixels[i]) << name << " " << i;
  }
}

TEST(ExrLayers, AMissingLayerIsNamed) {
  test::TempDir dir;
  const auto file = dir.path() / "plain.exr";
  const Image colour = ramp(4, 4, 0);
  save_exr_layers(file, {{"", &colour, "RGBA"}});
  try {
    load_exr_layer(file, "albedo");
    FAIL() << "no error";
  } catch (const ImageError& e) {
    EXPECT_NE(std::string(e.what()).find("plain.exr"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no layer 'albedo'"), std::string::npos) << e.what();
  }
}

TEST(ExrLayers, LayersMustShareOneSizeAndGoToAnExrFile) {
  test::TempDir dir;
  const Image a = ramp(4, 4, 0), b = ramp(5, 4, 0);
  EXPECT_THROW(save_exr_layers(dir.path() / "x.exr", {{"", &a, "RGBA"}, {"b", &b, "RGB"}}), ImageError);
  EXPECT_THROW(save_exr_layers(dir.path() / "x.png", {{"", &a, "RGBA"}}), ImageError);
}

}  // namespace
}  // namespace glint
