// `glint render` where the output cannot be written or the image cannot be held: a full disk
// fails the command (exit 1, the old image kept), a read-only folder or a name too long fails
// before rendering, a size beyond the film limits is refused before anything is allocated, by
// the command and by the renderer. Runs the command in-process (it makes its own EGL context).
// The editor's export has the same checks (tests/editor/export_output_test.cpp).
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "app/render_command.h"
#include "renderer/gl_context.h"
#include "renderer/gpu_renderer.h"
#include "renderer/image.h"
#include "renderer/project_file.h"
#include "tests/furnace_scene.h"
#include "tests/small_tmpfs.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {
namespace fs = std::filesystem;

#define REQUIRE_TMPFS(tmpfs) \
  if (!(tmpfs).mounted()) GTEST_SKIP() << (tmpfs).skip_reason()

// The line the command prints once its GL context exists: absent when it failed before.
constexpr const char* kStartedRendering = "glint: OpenGL ";

struct Result {
  int exit_code;
  std::string err;
};

// `glint render ARGS...` (the arguments after "render"), with its stderr.
Result render(std::vector<std::string> args) {
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  testing::internal::CaptureStderr();
  const int code = run_render_command(static_cast<int>(argv.size()), argv.data());
  return {code, testing::internal::GetCapturedStderr()};
}

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

using test::furnace_scene;

// The render fits nowhere: exit 1 naming the file and the reason; the old image is intact.
TEST(RenderOutput, FullDiskFailsAndKeepsTheOldImage) {
  test::TempDir dir;
  save_project(furnace_scene(), dir / "furnace.glint");
  test::SmallTmpfs tmpfs("64k");
  REQUIRE_TMPFS(tmpfs);
  const fs::path out = tmpfs / "out.exr";
  save_image(out, Image::filled(2, 2, 0.5f));
  const std::string old_bytes = read_bytes(out);
  ASSERT_GT(tmpfs.fill(), 0u);
  const Result run = render({(dir / "furnace.glint").string(), "-o", out.string(), "--spp", "1"});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("glint render: " + out.string() + ": "), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("No space left on device"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("wrote"), std::string::npos) << run.err;
  EXPECT_TRUE(read_bytes(out) == old_bytes);
  EXPECT_EQ(tmpfs.names(), (std::vector<std::string>{"filler", "out.exr"}));
}

TEST(RenderOutput, ReadOnlyFolderFailsBeforeRenderingWithTheReason) {
  test::TempDir dir;
  save_project(furnace_scene(), dir / "furnace.glint");
  test::SmallTmpfs tmpfs("64k");
  REQUIRE_TMPFS(tmpfs);
  if (const std::string problem = tmpfs.remount_read_only(); !problem.empty()) GTEST_SKIP() << problem;
  const fs::path out = tmpfs / "out.png";
  const Result run = render({(dir / "furnace.glint").string(), "-o", out.string(), "--spp", "1"});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find(out.string() + ": "), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("Read-only file system"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find(kStartedRendering), std::string::npos) << run.err;
}

// 250 bytes fit NAME_MAX with the fixed-length temporary name; 256 do not, and are refused
// before the render rather than after it.
TEST(RenderOutput, OutputNamesAreCheckedBeforeRendering) {
  test::TempDir dir;
  save_project(furnace_scene(), dir / "furnace.glint");
  const fs::path long_name = dir / (std::string(246, 'n') + ".png");
  Result run = render({(dir / "furnace.glint").string(), "-o", long_name.string(), "--spp", "1"});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(load_image(long_name, ColorEncoding::srgb).width, 32);
  const fs::path too_long = dir / (std::string(252, 'n') + ".png");
  run = render({(dir / "furnace.glint").string(), "-o", too_long.string(), "--spp", "1"});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("File name too long"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find(kStartedRendering), std::string::npos) << run.err;
  EXPECT_LT(run.err.size(), 700u) << run.err;
}

// --width/--height have the film's limits and memory estimate, checked before any GPU memory
// is allocated (exit 2: bad arguments); one side given keeps the project's aspect.
TEST(RenderOutput, CommandLineSizesHaveTheFilmLimits) {
  test::TempDir dir;
  save_project(furnace_scene(32, 16), dir / "wide.glint");
  const std::string project = (dir / "wide.glint").string(), out = (dir / "out.exr").string();
  struct Case {
    std::vector<std::string> size;
    std::string message;
  } cases[] = {
      {{"--width", "16384", "--height", "8192"},
       "--width 16384 --height 8192 gives a 16384x8192 image: a 16384x8192 film would need 8.5 GiB "
       "of GPU buffers (68 bytes per pixel), the limit is 4.2 GiB (67108864 pixels, e.g. 8192x8192)"},
      {{"--height", "16384"},
       "--height 16384 gives a 32768x16384 image: the width must be an integer in [1, 16384] (got "
       "32768); a 32768x16384 film would need"},
      {{"--width", "16384"}, "--width 16384 gives a 16384x8192 image: a 16384x8192 film would need"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args = {project, "-o", out};
    args.insert(args.end(), c.size.begin(), c.size.end());
    const Result run = render(args);
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_NE(run.err.find("glint render: " + c.message), std::string::npos) << run.err;
    EXPECT_EQ(run.err.find(kStartedRendering), std::string::npos) << run.err;
  }
  EXPECT_FALSE(fs::exists(out));
  // At the limit (8192x8192 pixels in all) the size is accepted; 1 spp of 64x8192 renders.
  const Result run = render({project, "-o", out, "--width", "64", "--height", "8192", "--spp", "1"});
  EXPECT_EQ(run.exit_code, 0) << run.err;
}

// The renderer itself refuses a film beyond the limits, whoever asks, before it changes
// anything: it still renders at its previous size afterwards.
TEST(RenderOutput, RendererRefusesAFilmOverTheLimit) {
  auto context = HeadlessGLContext::create();
  GpuRenderer renderer;
  const Scene scene = furnace_scene(8, 8);
  renderer.sync(scene, 8, 8);
  try {
    renderer.sync(scene, 16384, 8192);
    ADD_FAILURE() << "the renderer accepted a 16384x8192 film";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("cannot render a 16384x8192 image: film: a 16384x8192 film would need", 0), 0u)
        << e.what();
  }
  EXPECT_THROW(renderer.sync(scene, 16385, 1), std::runtime_error);
  renderer.trace(1);
  const Image image = renderer.read_accumulation();
  EXPECT_EQ(image.width, 8);
  EXPECT_NEAR(image.at(0, 0)[0], 0.25f, 1e-4f);
}

}  // namespace
}  // namespace glint
