// The export dialog's "Transparent background" (ExportSettings::alpha): the export renders with
// the environment transparent and writes the coverage as alpha; HDR is refused.
#include <gtest/gtest.h>

#include "editor/export_job.h"
#include "renderer/gl_context.h"
#include "renderer/image.h"
#include "tests/furnace_scene.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

TEST(ExportAlpha, PngAndExrCarryTheCoverage) {
  auto context = HeadlessGLContext::create();
  test::TempDir dir;
  for (const char* name : {"a.png", "a.exr"}) {
    SCOPED_TRACE(name);
    ExportSettings s;
    s.width = 32;
    s.height = 32;
    s.samples = 16;
    s.alpha = true;
    s.output = dir / name;
    ExportJob job(test::furnace_scene(32, 32), s);
    while (job.step(0.01)) {
    }
    ASSERT_EQ(job.state(), ExportJob::State::done) << job.error();
    const Image img = load_image(s.output, ColorEncoding::linear);
    EXPECT_EQ(img.at(16, 16)[3], 1.0f);
    EXPECT_EQ(img.at(0, 0)[3], 0.0f);
    int fractional = 0;
    for (size_t i = 3; i < img.pixels.size(); i += 4) fractional += img.pixels[i] > 0 && img.pixels[i] < 1;
    EXPECT_GT(fractional, 10);
  }
  ExportSettings hdr;
  hdr.output = dir / "a.hdr";
  hdr.alpha = true;
  EXPECT_EQ(validate_export_settings(hdr), "a transparent background needs PNG or EXR (HDR has no alpha)");
}

}  // namespace
}  // namespace glint
