// `glint render --reference REF --log OUT.csv`: the convergence log of a noisy scene
// against an independent reference, a white furnace against its exact image, and the errors:
// a log path that names an input or the output, a log that cannot be written.
// Runs the command in-process; it makes its own headless EGL context.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "app/render_command.h"
#include "renderer/image.h"
#include "renderer/project_file.h"
#include "tests/furnace_scene.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {
namespace fs = std::filesystem;

const char* const kHeader = "spp,seconds,gpu_seconds,relmse,estimated_relmse,relmse_trimmed,mape,mean_bias,nonfinite";

// `glint render ARGS...`: the arguments after "render", as main passes them.
int render(std::vector<std::string> args) {
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  return run_render_command(static_cast<int>(argv.size()), argv.data());
}

struct Row {
  long long spp = 0;
  double seconds, gpu_seconds, relmse, estimated_relmse, relmse_trimmed, mape, mean_bias, nonfinite;
};

// Reads the log, checking the header and that every row has exactly nine numbers.
std::vector<Row> read_log(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  EXPECT_TRUE(std::getline(in, line)) << file << " is empty";
  EXPECT_EQ(line, kHeader);
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::stringstream ss(line);
    for (std::string field; std::getline(ss, field, ',');) v.push_back(std::stod(field));
    EXPECT_EQ(v.size(), 9u) << line;
    if (v.size() != 9) continue;
    rows.push_back({static_cast<long long>(v[0]), v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]});
  }
  return rows;
}

std::vector<long long> spp_column(const std::vector<Row>& rows) {
  std::vector<long long> s;
  for (const Row& r : rows) s.push_back(r.spp);
  return s;
}

using test::furnace_scene;

Image constant_image(int w, int h, float r, float g, float b) {
  Image img;
  img.width = w;
  img.height = h;
  for (int i = 0; i < w * h; ++i) img.pixels.insert(img.pixels.end(), {r, g, b, 1.0f});
  return img;
}

// The Cornell box at 32x32 against a 256-spp reference of another seed (independent noise), to
// 48 spp: checkpoints at the powers of two and at 48. The expected relMSE falls like
// var/N + var/256, from ~1.004 var at 1 spp to ~0.025 var at 48.
TEST(RenderLog, NoisySceneConvergesTowardsAnIndependentReference) {
  test::TempDir dir;
  const std::string project = (fs::path(GLINT_SOURCE_DIR) / "projects/cornell_box.glint").string();
  ASSERT_EQ(render({project, "-o", (dir / "ref.exr").string(), "--width", "32", "--spp", "256",
                    "--seed", "1000"}), 0);
  ASSERT_EQ(render({project, "-o", (dir / "out.exr").string(), "--width", "32", "--spp", "48",
                    "--seed", "1", "--reference", (dir / "ref.exr").string(), "--log",
                    (dir / "log.csv").string()}), 0);
  std::vector<Row> rows = read_log(dir / "log.csv");
  ASSERT_EQ(spp_column(rows), (std::vector<long long>{1, 2, 4, 8, 16, 32, 48}));
  for (size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    for (double v : {r.seconds, r.gpu_seconds, r.relmse, r.relmse_trimmed, r.mape, r.mean_bias})
      EXPECT_TRUE(std::isfinite(v)) << "row " << i;
    EXPECT_GT(r.seconds, 0);
    EXPECT_GT(r.gpu_seconds, 0);
    EXPECT_LE(r.relmse_trimmed, r.relmse);
    // The estimate needs two samples per pixel; from then on it is a positive number.
    if (r.spp >= 2) EXPECT_GT(r.estimated_relmse, 0) << "row " << i;
    else EXPECT_TRUE(std::isnan(r.estimated_relmse)) << "row " << i;
    EXPECT_EQ(r.nonfinite, 0);
    if (i > 0) {
      EXPECT_GT(r.seconds, rows[i - 1].seconds);
      EXPECT_GT(r.gpu_seconds, rows[i - 1].gpu_seconds);
    }
  }
  // With light sampling the remaining error is a heavy tail (caustic paths: the lamp seen in
  // the mirror sphere, found by BSDF sampling only), so the relMSE of one run jumps by up to
  // 10x between checkpoints (measured: 0.15 at 1 spp, 1.77 at 2, 0.066 at 48). It still falls
  // from 1 to 48 spp (a firefly's share drops by 48^2), and MAPE, which a few pixels cannot
  // dominate, falls like 1/sqrt(N) down to the 256-spp reference's own noise (measured 0.42 at
  // 1 spp and 0.15 at 48, with either sampler): at least by 2.
  EXPECT_LT(rows.back().relmse, rows.front().relmse);
  EXPECT_LT(rows.back().relmse_trimmed, rows.front().relmse_trimmed);
  EXPECT_LT(rows.back().mape, rows.front().mape / 2);
}

// Zero-variance scene against its exact image: every row's error is float rounding only
// (per-pixel error below 1e-5 relative, as in the GL white furnace test).
TEST(RenderLog, WhiteFurnaceMatchesItsExactImageAtEveryCheckpoint) {
  test::TempDir dir;
  save_project(furnace_scene(), dir / "furnace.glint");
  save_image(dir / "exact.exr", constant_image(32, 32, 0.25f, 0.5f, 1.0f));
  ASSERT_EQ(render({(dir / "furnace.glint").string(), "-o", (dir / "out.hdr").string(), "--spp", "8",
                    "--reference", (dir / "exact.exr").string(), "--log", (dir / "log.csv").string()}), 0);
  std::vector<Row> rows = read_log(dir / "log.csv");
  ASSERT_EQ(spp_column(rows), (std::vector<long long>{1, 2, 4, 8}));
  for (const Row& r : rows) {
    EXPECT_LT(r.relmse, 1e-9);
    EXPECT_LT(r.relmse_trimmed, 1e-9);
    if (r.spp >= 2) {
      EXPECT_LT(r.estimated_relmse, 1e-9);  // no variance to estimate
    }
    EXPECT_LT(r.mape, 1e-5);
    EXPECT_LT(std::abs(r.mean_bias), 1e-5);
    EXPECT_EQ(r.nonfinite, 0);
  }
}

TEST(RenderLog, TimeLimitedRenderLogsPowersOfTwo) {
  test::TempDir dir;
  save_project(furnace_scene(), dir / "furnace.glint");
  save_image(dir / "exact.exr", constant_image(32, 32, 0.25f, 0.5f, 1.0f));
  ASSERT_EQ(render({(dir / "furnace.glint").string(), "-o", (dir / "out.exr").string(), "--time", "0.5",
                    "--reference", (dir / "exact.exr").string(), "--log", (dir / "log.csv").string()}), 0);
  std::vector<Row> rows = read_log(dir / "log.csv");
  ASSERT_FALSE(rows.empty());
  for (size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i].spp, 1LL << i);
}

// --target-error: the zero-variance furnace meets any target at the first sample count allowed
// (16 spp); an unreachable one stops at the --spp cap; the last line names the limit.
TEST(RenderTargetError, SaysWhichLimitEndedTheRender) {
  test::TempDir dir;
  save_project(furnace_scene(), dir / "furnace.glint");
  const std::string project = (dir / "furnace.glint").string(), out = (dir / "out.exr").string();
  testing::internal::CaptureStderr();
  EXPECT_EQ(render({project, "-o", out, "--target-error", "1e-6"}), 0);
  std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("stopped by the error target: estimated relMSE "), std::string::npos) << err;
  EXPECT_NE(err.find("(target 1e-06) at 16 spp"), std::string::npos) << err;
  Scene noisy = furnace_scene();
  noisy.materials[0].color = {0.5f, 0.5f, 0.5f};
  noisy.quads.push_back({.name = "lamp", .material = "lamp",
                         .corners = {glm::vec3{-1, 2, -1}, glm::vec3{-1, 2, 1}, glm::vec3{1, 2, -1}, glm::vec3{1, 2, 1}}});
  noisy.materials.push_back({.name = "lamp", .color = {0, 0, 0}, .emission = {20, 20, 20}});
  save_project(noisy, dir / "noisy.glint");
  testing::internal::CaptureStderr();
  EXPECT_EQ(render({(dir / "noisy.glint").string(), "-o", out, "--target-error", "1e-12", "--spp", "20"}), 0);
  err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("stopped by the sample count"), std::string::npos) << err;
  EXPECT_NE(err.find("at 20 spp"), std::string::npos) << err;
  testing::internal::CaptureStderr();
  EXPECT_EQ(render({project, "-o", out, "--target-error", "0"}), 2);
  err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("--target-error expects a positive relMSE, got '0'"), std::string::npos) << err;
}

// --restart picks path regeneration's policy (the same image either way) and names a bad value.
TEST(RenderLog, RestartPolicyRendersAndRejectsUnknownValues) {
  test::TempDir dir;
  save_project(furnace_scene(), dir / "furnace.glint");
  const std::string project = (dir / "furnace.glint").string(), out = (dir / "out.exr").string();
  for (const char* policy : {"auto", "at-once", "together"}) {
    testing::internal::CaptureStderr();
    EXPECT_EQ(render({project, "-o", out, "--spp", "2", "--restart", policy}), 0) << policy;
    testing::internal::GetCapturedStderr();
  }
  testing::internal::CaptureStderr();
  EXPECT_EQ(render({project, "-o", out, "--restart", "sideways"}), 2);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("--restart expects auto, at-once or together, got 'sideways'"), std::string::npos) << err;
}

TEST(RenderLog, ReferenceAndLogGoTogether) {
  test::TempDir dir;
  save_project(furnace_scene(), dir / "furnace.glint");
  const std::string project = (dir / "furnace.glint").string(), out = (dir / "out.exr").string();
  testing::internal::CaptureStderr();
  EXPECT_EQ(render({project, "-o", out, "--log", (dir / "log.csv").string()}), 2);
  EXPECT_NE(testing::internal::GetCapturedStderr().find("--log needs --reference"), std::string::npos);
  testing::internal::CaptureStderr();
  EXPECT_EQ(render({project, "-o", out, "--reference", (dir / "ref.exr").string()}), 2);
  EXPECT_NE(testing::internal::GetCapturedStderr().find("--reference needs --log"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "log.csv"));
}

TEST(RenderLog, BadReferenceFailsBeforeRenderingAndNamesTheFile) {
  test::TempDir dir;
  save_project(furnace_scene(), dir / "furnace.glint");
  const std::string project = (dir / "furnace.glint").string(), out = (dir / "out.exr").string();
  const std::string log = (dir / "log.csv").string();
  save_image(dir / "small.exr", constant_image(16, 32, 1, 1, 1));
  save_image(dir / "display.png", constant_image(32, 32, 1, 1, 1));
  struct Case {
    std::string reference, message;
  } cases[] = {
      {(dir / "small.exr").string(), "is 16x32 but the render is 32x32"},
      {(dir / "missing.exr").string(), "missing.exr"},
      {(dir / "display.png").string(), "must be linear radiance"},
  };
  for (const Case& c : cases) {
    testing::internal::CaptureStderr();
    EXPECT_EQ(render({project, "-o", out, "--reference", c.reference, "--log", log}), 1) << c.reference;
    std::string err = testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find(c.reference), std::string::npos) << err;
    EXPECT_NE(err.find(c.message), std::string::npos) << err;
  }
  EXPECT_FALSE(fs::exists(out));
}

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// --log (and -o) must not name a file the command reads, nor each other: refused before
// anything is written or rendered (exit 2), the files untouched. The same file is found through
// a symbolic link, a hard link and a path spelled differently.
TEST(RenderLog, RefusesToOverwriteTheProjectTheReferenceOrTheOutput) {
  test::TempDir dir;
  save_project(furnace_scene(), dir / "furnace.glint");
  save_image(dir / "exact.exr", constant_image(32, 32, 0.25f, 0.5f, 1.0f));
  fs::create_symlink("furnace.glint", dir / "link.csv");
  fs::create_hard_link(dir / "exact.exr", dir / "hard.csv");
  const std::string project_bytes = read_bytes(dir / "furnace.glint");
  const std::string reference_bytes = read_bytes(dir / "exact.exr");
  const std::string project = (dir / "furnace.glint").string(), reference = (dir / "exact.exr").string();
  const std::string out = (dir / "out.exr").string();
  struct Case {
    std::string output, log, message;
  } cases[] = {
      {out, project, "--log " + project + " is the project"},
      {out, (dir / "sub/../furnace.glint").string(), "is the project"},
      {out, (dir / "link.csv").string(), "is the project"},
      {out, reference, "--log " + reference + " is the reference"},
      {out, (dir / "hard.csv").string(), "is the reference"},
      {out, out, "--log " + out + " is the output image"},
      {reference, (dir / "log.csv").string(), "-o " + reference + " is the reference"},
  };
  fs::create_directories(dir / "sub");
  for (const Case& c : cases) {
    testing::internal::CaptureStderr();
    EXPECT_EQ(render({project, "-o", c.output, "--spp", "1", "--reference", reference, "--log", c.log}), 2)
        << c.log;
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find(c.message), std::string::npos) << err;
    EXPECT_EQ(err.find("glint: OpenGL"), std::string::npos) << err;
  }
  EXPECT_TRUE(read_bytes(dir / "furnace.glint") == project_bytes);
  EXPECT_TRUE(read_bytes(dir / "exact.exr") == reference_bytes);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(dir / "log.csv"));
}

// A log that cannot be written fails the command with the OS reason (exit 1), before the
// render when the header already fails (/dev/full), never "wrote".
TEST(RenderLog, FailedLogWritesFailTheCommand) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  test::TempDir dir;
  save_project(furnace_scene(), dir / "furnace.glint");
  save_image(dir / "exact.exr", constant_image(32, 32, 0.25f, 0.5f, 1.0f));
  testing::internal::CaptureStderr();
  EXPECT_EQ(render({(dir / "furnace.glint").string(), "-o", (dir / "out.exr").string(), "--spp", "2",
                    "--reference", (dir / "exact.exr").string(), "--log", "/dev/full"}), 1);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("glint render: /dev/full: cannot write the log: No space left on device"),
            std::string::npos) << err;
  EXPECT_EQ(err.find("wrote"), std::string::npos) << err;
  EXPECT_EQ(err.find("glint: OpenGL"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

}  // namespace
}  // namespace glint
