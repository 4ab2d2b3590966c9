// libFuzzer target: bytes through the image readers (PNG, JPEG and Radiance HDR via stb_image,
// OpenEXR via tinyexr, told apart by signature), as images and as textures. Any input must
// either decode to an image that agrees with its header probe or throw ImageError.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "renderer/image.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::vector<unsigned char> bytes(data, data + size);
  glint::ImageInfo info;
  try {
    info = glint::probe_image_data(bytes, "fuzz");
  } catch (const glint::ImageError&) {
    info = {};
  }
  try {
    const glint::Image image = glint::load_image_data(bytes, "fuzz", glint::ColorEncoding::srgb);
    if (image.width <= 0 || image.height <= 0 ||
        image.pixels.size() != size_t(image.width) * image.height * 4)
      std::abort();
    if (info.width != 0 && (info.width != image.width || info.height != image.height)) std::abort();
  } catch (const glint::ImageError&) {
  }
  // The texture reader (8-bit kept 8-bit, texels checked): the same size, and a consistent
  // store (bytes for 8-bit sources, finite non-negative floats otherwise).
  try {
    const glint::TextureImage texture = glint::load_texture_image_data(bytes, "fuzz");
    const size_t texels = size_t(texture.width()) * texture.height();
    if (texture.width() <= 0 || texture.height() <= 0) std::abort();
    if (info.width != 0 && (info.width != texture.width() || info.height != texture.height())) std::abort();
    if (texture.eight_bit() ? texture.rgba8.size() != texels * 4 : texture.linear.pixels.size() != texels * 4)
      std::abort();
    for (float v : texture.linear.pixels)
      if (!std::isfinite(v) || v < 0) std::abort();
  } catch (const glint::ImageError&) {
  }
  return 0;
}
