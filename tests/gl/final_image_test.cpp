// The final images (renderer/render_output.h): every PNG is the CPU tonemap of the linear
// colour, whoever writes it, and that tonemap agrees with the GPU's display pass (the same
// formula, shaders/lib/tonemap.glsl) to one 8-bit level; HDR and EXR hold the linear colour with
// alpha 1.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "renderer/project_file.h"
#include "renderer/render_output.h"
#include "tests/gl/gl_test_support.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

std::string read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

int level(float v) { return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

// On every example project: the PNG written from the renderer is byte for byte the CPU tonemap
// of its colour, and differs from the GPU's display image by at most one level (where the
// driver's arithmetic rounds differently); the count of such channels is printed.
TEST(FinalImage, PngIsTheCpuTonemapWithinOneLevelOfTheDisplay) {
  test::ensure_gl_context();
  test::TempDir dir;
  long channels = 0, differing = 0;
  int projects = 0;
  for (const auto& entry : std::filesystem::directory_iterator(GLINT_SOURCE_DIR "/projects")) {
    if (entry.path().extension() != ".glint") continue;
    SCOPED_TRACE(entry.path().filename().string());
    const Scene scene = load_project(entry.path());
    GpuRenderer r;
    const int w = 96, h = std::max(1, w * scene.film.height / scene.film.width);
    r.sync(scene, w, h);
    r.trace(4);
    const std::filesystem::path written = dir / "written.png", expected = dir / "expected.png";
    save_render_output(r, scene.display, written, {});
    save_image(expected, tonemapped(render_colour(r), scene.display));
    EXPECT_TRUE(read_bytes(written) == read_bytes(expected));
    const Image png = load_image(written, ColorEncoding::linear), display = r.read_display();
    ASSERT_EQ(png.pixels.size(), display.pixels.size());
    for (size_t i = 0; i < png.pixels.size(); ++i) {
      const int difference = std::abs(level(png.pixels[i]) - level(display.pixels[i]));
      ASSERT_LE(difference, 1) << "channel " << i;
      differing += difference;
      ++channels;
    }
    ++projects;
  }
  EXPECT_GE(projects, 6);
  std::printf("PNG vs GPU display: %ld of %ld channels one level apart\n", differing, channels);
}

// HDR and EXR hold the accumulation's colour with alpha 1 (its alpha is the discarded count).
TEST(FinalImage, LinearFormatsHoldTheColourWithAlphaOne) {
  test::ensure_gl_context();
  test::TempDir dir;
  Scene scene = test::empty_scene();
  scene.environment.color = {0.25f, 0.5f, 1.0f};
  GpuRenderer r;
  r.sync(scene, 8, 4);
  r.trace(2);
  const Image colour = r.read_accumulation();
  for (const char* name : {"out.exr", "out.hdr"}) {
    SCOPED_TRACE(name);
    save_render_output(r, scene.display, dir / name, {});
    const Image read = load_image(dir / name, ColorEncoding::linear);
    ASSERT_EQ(read.pixels.size(), colour.pixels.size());
    for (size_t i = 0; i < read.pixels.size(); ++i) {
      if (i % 4 == 3)
        EXPECT_EQ(read.pixels[i], 1.0f);
      else
        EXPECT_NEAR(read.pixels[i], colour.pixels[i], 0.01f);  // RGBE: 8 bits under a shared exponent
    }
  }
}

}  // namespace
}  // namespace glint
