// Writes the procedural assets that the example projects use:
//   glint-make-assets OUTPUT_FOLDER
// Colour textures are stored sRGB-encoded (8-bit PNG), roughness maps as linear grey, the sky as
// a linear Radiance .hdr. The output is deterministic, so re-running it changes no file.
#include <cstdio>
#include <exception>
#include <filesystem>

#include "renderer/image.h"
#include "renderer/procedural_assets.h"

namespace {

// Linear colour to the sRGB-encoded values that an 8-bit colour texture stores; alpha stays linear.
glint::Image encode_srgb(glint::Image image) {
  for (size_t i = 0; i < image.pixels.size(); i += 4)
    for (int c = 0; c < 3; ++c) image.pixels[i + c] = glint::linear_to_srgb(image.pixels[i + c]);
  return image;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_FOLDER\n", argc > 0 ? argv[0] : "glint-make-assets");
    return 2;
  }
  namespace gp = glint::procedural;
  const std::filesystem::path out = argv[1];
  try {
    std::filesystem::create_directories(out);
    auto write = [&](const char* name, const glint::Image& image) {
      glint::save_image(out / name, image);
      std::printf("wrote %s\n", (out / name).string().c_str());
    };
    write("wood_color.png", encode_srgb(gp::wood_color()));
    write("wood_roughness.png", gp::wood_roughness());
    write("leather_color.png", encode_srgb(gp::leather_color()));
    write("leather_roughness.png", gp::leather_roughness());
    write("metal_color.png", encode_srgb(gp::metal_color()));
    write("metal_roughness.png", gp::metal_roughness());
    write("checker.png", encode_srgb(gp::checker_with_holes()));
    write("sky.hdr", gp::sky());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
