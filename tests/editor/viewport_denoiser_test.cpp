// The viewport's Denoise toggle (editor/viewport_denoiser.h): the denoised image replaces the
// noisy one once the worker has returned one, the accumulation goes on, and turning it off
// shows the renderer's own image again.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "editor/viewport_renderer.h"
#include "renderer/denoiser.h"
#include "renderer/gl_context.h"
#include "renderer/project_file.h"

namespace glint {
namespace {

TEST(ViewportDenoiser, ShowsTheDenoisedImageWhileTheAccumulationContinues) {
  auto context = HeadlessGLContext::create();
  const Scene scene = load_project(std::filesystem::path(GLINT_SOURCE_DIR) / "projects/default.glint");
  ViewportRenderer viewport;
  ViewportRequest request;
  request.width = 32;
  request.height = 24;
  request.resolution = ViewportResolution::full;
  request.samples_per_frame = 1;
  request.denoise = true;
  ViewportFrame frame;
  if (const auto why = denoising_unavailable()) {
    if (GLINT_OIDN_BUNDLED) FAIL() << "the build bundled Open Image Denoise but it did not load: " << *why;
    frame = viewport.render(scene, request);
    EXPECT_EQ(frame.display_texture, viewport.renderer().display_texture());
    EXPECT_NE(frame.stats.denoise_status.find("unavailable"), std::string::npos);
    GTEST_SKIP() << "Open Image Denoise is not available: " << *why;
  }
  // The worker takes a moment (llvmpipe and a loaded CPU): up to a minute of frames.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  do {
    frame = viewport.render(scene, request);
    if (frame.display_texture != viewport.renderer().display_texture()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  } while (std::chrono::steady_clock::now() < give_up);
  ASSERT_NE(frame.display_texture, viewport.renderer().display_texture()) << frame.stats.denoise_status;
  EXPECT_NE(frame.stats.denoise_status.find("denoised (biased) at"), std::string::npos)
      << frame.stats.denoise_status;
  const int64_t spp = frame.stats.spp;
  frame = viewport.render(scene, request);
  EXPECT_EQ(frame.stats.spp, spp + 1) << "the accumulation goes on underneath";
  request.denoise = false;
  frame = viewport.render(scene, request);
  EXPECT_EQ(frame.display_texture, viewport.renderer().display_texture());
  EXPECT_FALSE(viewport.renderer().aovs_enabled());
}

}  // namespace
}  // namespace glint
