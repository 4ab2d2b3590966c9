// Writes synthetic render parts of one render for merge tests and measurements:
//   glint-make-test-parts FOLDER COUNT WIDTH HEIGHT
// FOLDER/part-0000.exr ... part-<COUNT-1>.exr hold samples i:i+1 each (the same digest, size,
// seed, sampler and display settings), with values that depend on the pixel and the part and a
// few discarded samples, written by save_part_image as `glint render --samples` writes parts.
// Cheap to make (no rendering, small ZIP-compressed files), and as large in memory as real
// parts of that size.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "renderer/image.h"
#include "renderer/render_part.h"
#include "renderer/scene_validation.h"

namespace {

constexpr const char* kUsage =
    "usage: glint-make-test-parts FOLDER COUNT WIDTH HEIGHT\n"
    "Writes COUNT synthetic parts (samples i:i+1) of a WIDTH x HEIGHT render into FOLDER.\n";

bool parse_int(const char* text, long max, long& out) {
  char* end = nullptr;
  out = std::strtol(text, &end, 10);
  return *text != '\0' && *end == '\0' && out >= 1 && out <= max;
}

}  // namespace

int main(int argc, char** argv) {
  long count = 0, width = 0, height = 0;
  if (argc != 5 || !parse_int(argv[2], 100000, count) || !parse_int(argv[3], glint::kMaxFilmSide, width) ||
      !parse_int(argv[4], glint::kMaxFilmSide, height) || width * height > glint::kMaxFilmPixels) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  try {
    const std::filesystem::path folder = argv[1];
    std::filesystem::create_directories(folder);
    glint::PartInfo info;
    info.digest = 0x5eed5eed5eed5eedull;
    info.width = static_cast<int>(width);
    info.height = static_cast<int>(height);
    info.seed = 1;
    glint::Image image{info.width, info.height, std::vector<float>(size_t(width) * size_t(height) * 4)};
    for (long i = 0; i < count; ++i) {
      info.range = {i, i + 1};
      for (int y = 0; y < info.height; ++y)
        for (int x = 0; x < info.width; ++x) {
          float* v = image.at(x, y);
          const bool discarded = (long(x) * 31 + long(y) * 17 + i) % 997 == 0;
          v[0] = discarded ? 0.0f : float((x + 3 * i) % 16) / 16.0f;
          v[1] = discarded ? 0.0f : float(y % 8) / 8.0f;
          v[2] = discarded ? 0.0f : 0.25f * float(i % 4);
          v[3] = discarded ? 1.0f : 0.0f;
        }
      char name[32];
      std::snprintf(name, sizeof name, "part-%04ld.exr", i);
      glint::save_part_image(folder / name, info, image);
    }
    std::fprintf(stderr, "glint-make-test-parts: wrote %ld parts of %ldx%ld in %s\n", count, width, height,
                 folder.string().c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint-make-test-parts: %s\n", e.what());
    return 1;
  }
}
