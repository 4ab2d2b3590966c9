// `glint render --alpha`: a transparent background, in-process (it makes its own EGL context).
// The furnace's sphere in front of its environment: alpha 1 at the centre, 0 in the corners,
// fractional on the edge; the EXR premultiplied, the PNG straight. Bad combinations exit 2.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/render_command.h"
#include "renderer/image.h"
#include "renderer/project_file.h"
#include "tests/furnace_scene.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

int render(std::vector<std::string> args, std::string* err = nullptr) {
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  testing::internal::CaptureStderr();
  const int code = run_render_command(static_cast<int>(argv.size()), argv.data());
  const std::string text = testing::internal::GetCapturedStderr();
  if (err) *err = text;
  return code;
}

TEST(RenderAlpha, CoverageIsTheAlphaOfPngAndExr) {
  test::TempDir dir;
  save_project(test::furnace_scene(32, 32), dir / "furnace.glint");
  std::string err;
  for (const char* name : {"a.exr", "a.png"})
    ASSERT_EQ(render({(dir / "furnace.glint").string(), "-o", (dir / name).string(), "--spp", "32", "--alpha"}, &err), 0)
        << err;
  const Image exr = load_image(dir / "a.exr", ColorEncoding::linear);
  const Image png = load_image(dir / "a.png", ColorEncoding::linear);
  EXPECT_EQ(exr.at(16, 16)[3], 1.0f);
  EXPECT_EQ(exr.at(0, 0)[3], 0.0f);
  EXPECT_EQ(exr.at(0, 0)[2], 0.0f);  // the environment adds no colour
  EXPECT_EQ(png.at(16, 16)[3], 1.0f);
  EXPECT_EQ(png.at(0, 0)[3], 0.0f);
  int fractional = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const float a = exr.at(x, y)[3];
      if (a > 0 && a < 1) {
        ++fractional;
        EXPECT_NEAR(exr.at(x, y)[2], a * 1.0f, 1e-5);  // premultiplied: L.b = 1
        EXPECT_NEAR(png.at(x, y)[3], a, 0.5 / 255 + 1e-6);
        EXPECT_NEAR(png.at(x, y)[2], png.at(16, 16)[2], 1.5 / 255);  // straight
      }
    }
  EXPECT_GT(fractional, 10);
}

TEST(RenderAlpha, RefusedForHdrAndParts) {
  std::string err;
  EXPECT_EQ(render({"x.glint", "-o", "x.hdr", "--alpha"}, &err), 2);
  EXPECT_NE(err.find("--alpha needs a .png or .exr output (.hdr has no alpha)"), std::string::npos) << err;
  EXPECT_EQ(render({"x.glint", "-o", "x.exr", "--samples", "0:4", "--alpha"}, &err), 2);
  EXPECT_NE(err.find("--alpha is not for parts"), std::string::npos) << err;
}

}  // namespace
}  // namespace glint
