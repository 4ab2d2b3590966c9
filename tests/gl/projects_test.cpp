// (f) Every example project loads, renders without NaN or Inf, and is neither black nor white.
#include <filesystem>

#include "renderer/project_file.h"
#include "tests/gl/gl_test_support.h"

namespace glint {
namespace {

TEST(GlProjects, EveryExampleRendersFiniteAndNotBlank) {
  test::ensure_gl_context();
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(GLINT_SOURCE_DIR "/projects")) {
    if (entry.path().extension() != ".glint") continue;
    SCOPED_TRACE(entry.path().filename().string());
    Scene scene = load_project(entry.path());
    GpuRenderer r;
    const int w = 64, h = std::max(1, 64 * scene.film.height / scene.film.width);
    r.sync(scene, w, h);
    r.trace(8);
    Image radiance = r.read_accumulation();
    EXPECT_TRUE(test::all_finite(radiance));
    auto everywhere = [](int, int) { return true; };
    EXPECT_EQ(test::channel_stats(radiance, 3, everywhere).mean, 0.0) << "non-finite samples were discarded";
    Image display = r.read_display();
    double mean = 0;
    for (int c = 0; c < 3; ++c) mean += test::channel_stats(display, c, everywhere).mean / 3;
    EXPECT_GT(mean, 0.05) << "all black";
    EXPECT_LT(mean, 0.95) << "all white";
    ++count;
  }
  EXPECT_GE(count, 6);
}

}  // namespace
}  // namespace glint
