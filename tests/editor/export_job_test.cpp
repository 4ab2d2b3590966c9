// The export job on a headless EGL context: tiny PNG and EXR of the default project, cancel.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>
#include <vector>

#include "editor/export_job.h"
#include "renderer/denoiser.h"
#include "renderer/gl_context.h"
#include "renderer/image.h"
#include "renderer/project_file.h"
#include "renderer/scene_validation.h"

namespace glint {
namespace {
namespace fs = std::filesystem;

class ExportJobTest : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = HeadlessGLContext::create();
    scene_ = load_project(fs::path(GLINT_SOURCE_DIR) / "projects/default.glint");
    dir_ = fs::temp_directory_path() / ("glint-export-test-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Steps like the UI does, a slice per "frame"; returns the number of slices.
  int run(ExportJob& job) {
    int slices = 0;
    while (job.step(0.01)) ++slices;
    return slices;
  }

  std::unique_ptr<HeadlessGLContext> context_;
  Scene scene_;
  fs::path dir_;
};

TEST_F(ExportJobTest, WritesATonemappedPngOfTheRequestedSize) {
  ExportSettings s;
  s.width = 32;
  s.height = 24;
  s.samples = 8;
  s.output = dir_ / "out.png";
  ExportJob job(scene_, s);
  run(job);
  ASSERT_EQ(job.state(), ExportJob::State::done) << job.error();
  EXPECT_EQ(job.samples(), 8);
  EXPECT_FLOAT_EQ(job.progress(), 1.0f);
  Image img = load_image(s.output, ColorEncoding::linear);
  EXPECT_EQ(img.width, 32);
  EXPECT_EQ(img.height, 24);
  float lo = 1, hi = 0;
  for (size_t i = 0; i < img.pixels.size(); i += 4) {
    lo = std::min(lo, img.pixels[i]);
    hi = std::max(hi, img.pixels[i]);
  }
  EXPECT_LT(lo, hi);  // an image, not a flat colour
}

TEST_F(ExportJobTest, WritesLinearExrWithAlphaOneInSlices) {
  ExportSettings s;
  s.width = 32;
  s.height = 32;
  s.samples = 16;
  s.output = dir_ / "out.exr";
  ExportJob job(scene_, s);
  // The first slice stops early enough that the UI would get its frame back.
  EXPECT_TRUE(job.step(0.0) || job.state() == ExportJob::State::done);
  EXPECT_LT(job.samples(), 16);
  run(job);
  ASSERT_EQ(job.state(), ExportJob::State::done) << job.error();
  Image img = load_image(s.output, ColorEncoding::linear);
  ASSERT_EQ(img.width, 32);
  ASSERT_EQ(img.height, 32);
  double sum = 0;
  for (size_t i = 0; i < img.pixels.size(); i += 4) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_TRUE(std::isfinite(img.pixels[i + c]));
      ASSERT_GE(img.pixels[i + c], 0.0f);
      sum += img.pixels[i + c];
    }
    EXPECT_EQ(img.pixels[i + 3], 1.0f);
  }
  EXPECT_GT(sum, 0);
}

TEST_F(ExportJobTest, TimeBudgetStopsAfterItsTime) {
  ExportSettings s;
  s.width = 16;
  s.height = 16;
  s.use_time = true;
  s.seconds = 0.2;
  s.output = dir_ / "timed.hdr";
  ExportJob job(scene_, s);
  run(job);
  ASSERT_EQ(job.state(), ExportJob::State::done) << job.error();
  EXPECT_GE(job.elapsed_seconds(), 0.2);
  EXPECT_GT(job.samples(), 0);
  EXPECT_TRUE(fs::exists(s.output));
}

// The dialog's time counts the wall clock, the UI's frames between slices included, not only
// the tracing (the time left would otherwise be too short by the UI's share of each frame).
TEST_F(ExportJobTest, WallSecondsCountTheTimeBetweenSlices) {
  ExportSettings s;
  s.width = 16;
  s.height = 16;
  s.samples = 1 << 20;
  s.output = dir_ / "wall.png";
  ExportJob job(scene_, s);
  for (int i = 0; i < 5; ++i) {
    job.step(0.001);
    std::this_thread::sleep_for(std::chrono::milliseconds(40));  // a slow UI frame
  }
  EXPECT_GE(job.wall_seconds(), 0.2);
  EXPECT_GE(job.wall_seconds(), job.elapsed_seconds() + 0.19);
  job.cancel();
}

// A pass that does not fit the slice is traced in bands over several steps. With a slice
// shorter than any row takes, every step traces exactly one row of the pass (the work of a step,
// independent of the device's speed); the file is still written once all passes are done.
TEST_F(ExportJobTest, AStepWithATinySliceTracesOneRow) {
  ExportSettings s;
  s.width = 40;
  s.height = 10;
  s.samples = 2;
  s.output = dir_ / "rows.png";
  ExportJob job(scene_, s);
  int steps = 0;
  float progress = 0;
  for (bool running = true; running;) {
    running = job.step(1e-9);
    ++steps;
    EXPECT_EQ(job.step_pixel_samples(), 40) << "step " << steps;
    EXPECT_GT(job.progress(), progress) << "step " << steps;
    progress = job.progress();
  }
  ASSERT_EQ(job.state(), ExportJob::State::done) << job.error();
  EXPECT_EQ(steps, 2 * 10);
  EXPECT_EQ(job.samples(), 2);
  EXPECT_TRUE(fs::exists(s.output));
}

// With a UI-sized slice (20 ms), steps stay near it even where a whole pass takes several
// slices (as on llvmpipe): every step traces,
// every row of every pass is traced once, and the median step is within a generous bound (4
// slices and 50 ms of slack, for a loaded machine).
TEST_F(ExportJobTest, StepsStayNearTheirSlice) {
  ExportSettings s;
  s.width = 320;
  s.height = 180;
  s.samples = 2;
  s.output = dir_ / "slices.png";
  // A first export of the same scene compiles its programs: seconds on llvmpipe when the
  // driver's shader cache is cold (a fresh checkout), and without a program worker (the editor
  // has one) that compile runs inside a step. The timed export below finds them cached.
  for (ExportJob warm_up(scene_, s); warm_up.step(1.0);) {
  }
  ExportJob job(scene_, s);
  constexpr double kSlice = 0.02;
  std::vector<double> seconds;
  int64_t traced = 0;
  for (bool running = true; running;) {
    const auto start = std::chrono::steady_clock::now();
    running = job.step(kSlice);
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    EXPECT_GT(job.step_pixel_samples(), 0);
    traced += job.step_pixel_samples();
  }
  ASSERT_EQ(job.state(), ExportJob::State::done) << job.error();
  EXPECT_EQ(traced, 2 * 320 * 180);
  seconds.pop_back();  // the step that wrote the file
  ASSERT_FALSE(seconds.empty());
  std::nth_element(seconds.begin(), seconds.begin() + seconds.size() / 2, seconds.end());
  EXPECT_LT(seconds[seconds.size() / 2], 4 * kSlice + 0.05);
}

TEST_F(ExportJobTest, CancelWritesNothing) {
  ExportSettings s;
  s.width = 32;
  s.height = 32;
  s.samples = 1 << 20;
  s.output = dir_ / "never.png";
  ExportJob job(scene_, s);
  job.step(0.0);
  job.cancel();
  EXPECT_EQ(job.state(), ExportJob::State::cancelled);
  EXPECT_FALSE(job.step(0.01));
  EXPECT_FALSE(fs::exists(s.output));
}

TEST_F(ExportJobTest, RejectsBadSettingsBeforeRendering) {
  ExportSettings s;
  s.output = dir_ / "x.jpg";
  EXPECT_NE(validate_export_settings(s), "");
  EXPECT_THROW(ExportJob(scene_, s), std::runtime_error);
  s.output = dir_ / "no-such-folder" / "x.png";
  EXPECT_NE(validate_export_settings(s).find("does not exist"), std::string::npos);
  s.output = dir_ / "x.png";
  s.width = 0;
  EXPECT_EQ(validate_export_settings(s), "the width must be an integer in [1, 16384] (got 0)");
}

// The export refuses what the project loader refuses, with the same memory estimate
// (check_film_size): 16384 x 16384 is within the side limit but needs 17 GiB of GPU buffers.
TEST_F(ExportJobTest, RefusesSizesOverTheFilmMemoryLimit) {
  ExportSettings s;
  s.output = dir_ / "x.png";
  s.width = 16384;
  s.height = 16384;
  const std::string expected =
      "a 16384x16384 film would need 17.0 GiB of GPU buffers (68 bytes per pixel), the limit is "
      "4.2 GiB (67108864 pixels, e.g. 8192x8192)";
  EXPECT_EQ(validate_export_settings(s), expected);
  EXPECT_EQ(validate_export_settings(s), check_film_size(16384, 16384)->problem);
  EXPECT_THROW(ExportJob(scene_, s), std::runtime_error);
  s.height = 16385;
  EXPECT_EQ(validate_export_settings(s).rfind("the height must be an integer in [1, 16384] (got 16385); a 16384x16385 film would need", 0), 0u);
  s.width = 8192;  // exactly the limit: accepted
  s.height = 8192;
  EXPECT_EQ(validate_export_settings(s), "");
  s.width = 8193;
  EXPECT_NE(validate_export_settings(s).find("would need"), std::string::npos);
}

// The export's Denoise option: the output is denoised on a worker and an EXR keeps the noisy
// colour, which is exactly the plain export's (the AOV pass leaves the colour alone).
TEST(ExportJobDenoise, DenoisedExrKeepsThePlainExportAsItsNoisyLayer) {
  auto context = HeadlessGLContext::create();
  const Scene scene = load_project(fs::path(GLINT_SOURCE_DIR) / "projects/default.glint");
  const fs::path dir = fs::temp_directory_path() / ("glint-export-denoise-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  ExportSettings s;
  s.width = 24;
  s.height = 16;
  s.samples = 4;
  s.output = dir / "plain.exr";
  ExportJob plain(scene, s);
  while (plain.step(0.01)) {
  }
  ASSERT_EQ(plain.state(), ExportJob::State::done) << plain.error();
  s.output = dir / "denoised.exr";
  s.denoise = true;
  ExportJob denoised(scene, s);
  while (denoised.step(0.01)) {
  }
  ASSERT_EQ(denoised.state(), ExportJob::State::done) << denoised.error();
  const Image noisy_plain = load_image(dir / "plain.exr", ColorEncoding::linear);
  if (const auto why = denoising_unavailable()) {
    EXPECT_NE(denoised.denoise_note().find("unavailable"), std::string::npos) << denoised.denoise_note();
    EXPECT_EQ(load_image(s.output, ColorEncoding::linear).pixels, noisy_plain.pixels);
  } else {
    EXPECT_NE(denoised.denoise_note().find("denoised (biased)"), std::string::npos) << denoised.denoise_note();
    EXPECT_EQ(load_exr_layer(s.output, "noisy").pixels, noisy_plain.pixels);
    EXPECT_NE(load_image(s.output, ColorEncoding::linear).pixels, noisy_plain.pixels);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace glint
