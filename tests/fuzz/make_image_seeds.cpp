// Writes the image fuzzer's seed corpus (tests/fuzz/corpus/image): 16x16 crops of the example
// assets in projects/assets, saved by the project's own writers as PNG, HDR (run-length and,
// below 8 pixels wide, flat scanlines) and EXR. Small on purpose: libFuzzer mutates them.
// Usage: make_image_seeds ASSETS_DIR OUT_DIR
#include <cstdio>
#include <filesystem>

#include "renderer/image.h"

using namespace glint;

static Image crop(const Image& in, int w, int h) {
  Image out{w, h, std::vector<float>(size_t(w) * h * 4)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c) out.at(x, y)[c] = in.at(x % in.width, y % in.height)[c];
  return out;
}

int main(int argc, char** argv) {
  if (argc != 3) return 2;
  const std::filesystem::path assets = argv[1], out = argv[2];
  std::filesystem::create_directories(out);
  const Image checker = load_image(assets / "checker.png", ColorEncoding::linear);  // has alpha
  const Image wood = load_image(assets / "wood_color.png", ColorEncoding::linear);
  const Image sky = load_image(assets / "sky.hdr", ColorEncoding::linear);
  save_image(out / "checker.png", crop(checker, 16, 16));
  save_image(out / "wood.png", crop(wood, 16, 16));
  save_image(out / "sky.hdr", crop(sky, 16, 8));
  save_image(out / "sky_flat.hdr", crop(sky, 4, 4));
  save_image(out / "sky.exr", crop(sky, 16, 8));
  save_image(out / "checker.exr", crop(checker, 8, 8));
  std::printf("wrote seeds to %s\n", out.c_str());
  return 0;
}
