// Checks the screenshot of the real window (editor.window_smoke runs `glint --screenshot` under
// Xvfb, then this test with GLINT_SMOKE_SCREENSHOT set): the viewport is not blank and the
// panels are drawn in Dear ImGui's dark style. Skipped when run on its own.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "renderer/image.h"

namespace glint {
namespace {

// Dear ImGui's dark style (StyleColorsDark, 1.93): the opaque panel background (0.18) and the
// opaque menu bar (0.14).
constexpr float kPanel = 0.18f;
constexpr float kMenuBar = 0.14f;
constexpr float kTolerance = 3.0f / 255;  // 8-bit rounding and blending

TEST(WindowSmoke, ScreenshotShowsTheViewportAndThePanels) {
  const char* file = std::getenv("GLINT_SMOKE_SCREENSHOT");
  if (!file) GTEST_SKIP() << "GLINT_SMOKE_SCREENSHOT not set (run through ctest -R editor.window_smoke)";
  Image img = load_image(file, ColorEncoding::linear);  // raw 8-bit values / 255
  ASSERT_GE(img.width, 640);
  ASSERT_GE(img.height, 400);
  const int W = img.width, H = img.height;
  auto expect_grey = [&](int x, int y, float value, const char* what) {
    const float* p = img.at(x, y);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(p[c], value, kTolerance) << what << " at (" << x << ", " << y << ") channel " << c;
  };
  expect_grey(W / 12, H * 9 / 10, kPanel, "outliner background");
  expect_grey(W - 12, H * 9 / 10, kPanel, "properties background");
  expect_grey(W - 8, 4, kMenuBar, "menu bar");

  // The viewport: the middle of the window holds a render with real variation.
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int y = H / 5; y < H * 4 / 5; y += 2)
    for (int x = W * 3 / 10; x < W * 7 / 10; x += 2) {
      const float* p = img.at(x, y);
      double l = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
      sum += l;
      sum2 += l * l;
      ++n;
    }
  double mean = sum / n, sd = std::sqrt(std::max(0.0, sum2 / n - mean * mean));
  EXPECT_GT(mean, 0.05) << "viewport too dark: blank?";
  EXPECT_LT(mean, 0.95) << "viewport too bright: blank?";
  EXPECT_GT(sd, 0.03) << "viewport has no variation: blank?";
}

}  // namespace
}  // namespace glint
