// The editor's export where the output cannot be written or the image cannot be held: it has
// the checks of `glint render` (tests/cli/render_output_test.cpp) and makes them when it
// starts, before its renderer exists.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "editor/export_job.h"
#include "renderer/gl_context.h"
#include "renderer/scene_validation.h"
#include "tests/furnace_scene.h"
#include "tests/small_tmpfs.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

using test::furnace_scene;

TEST(ExportOutput, ReadOnlyFolderFailsWhenTheExportStarts) {
  test::SmallTmpfs tmpfs("64k");
  if (!tmpfs.mounted()) GTEST_SKIP() << tmpfs.skip_reason();
  if (const std::string problem = tmpfs.remount_read_only(); !problem.empty()) GTEST_SKIP() << problem;
  auto context = HeadlessGLContext::create();
  ExportSettings settings;
  settings.width = settings.height = 16;
  settings.output = tmpfs / "out.png";
  try {
    ExportJob job(furnace_scene(), settings);
    ADD_FAILURE() << "an export to a read-only folder started";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("Read-only file system"), std::string::npos) << e.what();
  }
}

// The film's limits (validate_export_settings, and ExportJob throws).
TEST(ExportOutput, SizesHaveTheFilmLimits) {
  test::TempDir dir;
  ExportSettings settings;
  settings.width = 16384;
  settings.height = 8192;
  settings.output = dir / "out.png";
  EXPECT_EQ(validate_export_settings(settings), check_film_size(16384, 8192)->problem);
  EXPECT_THROW((ExportJob{furnace_scene(), settings}), std::runtime_error);
}

}  // namespace
}  // namespace glint
