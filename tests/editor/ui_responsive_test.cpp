// The editor answering while it works, driven headlessly (the fixture: ui_test_fixture.h): the
// viewport's long passes sliced into bands between frames, a native file dialog on a thread of
// its own, the start before the first image, the status line within the window, and the export
// dialog's framing, hover help and result.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <condition_variable>
#include <mutex>

#include <imgui_internal.h>

#include "editor/film_frame.h"
#include "editor/ui_layout.h"
#include "editor_test_util.h"
#include "ui_test_fixture.h"

namespace glint {
namespace {
namespace fs = std::filesystem;

using test::kProjects;
using test::UiTest;

// Preview > full on a window where one pass takes far longer than an idle frame may trace: the
// pass goes in bands of rows over several frames (the status line shows how far), each frame
// stays near the slice, and the samples arrive when a pass ends.
TEST_F(UiTest, LongPassesAreTracedInBandsBetweenFrames) {
  ImGui::GetIO().DisplaySize = ImVec2(1800, 1100);
  state_.viewport.resolution = ViewportResolution::full;
  mouse_to(ImVec2(-1, -1));  // idle
  FrameBudgetConfig c = viewport_->budget().config();
  c.idle_trace_seconds = 0.0005;
  viewport_->budget().set_config(c);
  const FrameStats& s = state_.viewport.frame.stats;
  for (int i = 0; i < 400 && s.spp < 2; ++i) frame();  // learns the cost of a pass
  ASSERT_GE(s.spp, 2) << s.trace_width << "x" << s.trace_height << " " << status_text();
  const int64_t pixels = int64_t(s.trace_width) * s.trace_height;
  const double pass = viewport_->budget().pass_seconds(pixels);
  ASSERT_GT(pass, 8 * c.idle_trace_seconds) << "a pass here fits a frame: nothing to slice";
  const int64_t start = s.spp;
  std::vector<double> frame_seconds;
  int banded = 0;
  for (int i = 0; i < 400 && s.spp < start + 2; ++i) {
    frame();
    frame_seconds.push_back(viewport_->traced_seconds());
    if (s.pass_progress > 0 && s.pass_progress < 1) ++banded;
    if (s.pass_progress > 0) {
      EXPECT_NE(status_text().find("(pass "), std::string::npos) << status_text();
    }
  }
  EXPECT_GE(s.spp, start + 2);
  EXPECT_GE(banded, 3);
  // Each frame traces a band, a fraction of the pass: the median frame's tracing is well under
  // a whole pass's (the sum over the frames of the two passes, halved). The UI's own cost, which
  // on llvmpipe can match a small pass, is not counted.
  double traced = 0;
  for (double f : frame_seconds) traced += f;
  const double per_pass = traced / double(s.spp - start);
  std::sort(frame_seconds.begin(), frame_seconds.end());
  const double median = frame_seconds[frame_seconds.size() / 2];
  EXPECT_LT(median, 0.5 * per_pass) << "a whole pass traced " << per_pass << " s";
}

// A native file dialog blocks its thread, not the editor's: the viewport keeps accumulating
// while it is open, a modal keeps clicks and keys off the editor, and the chosen file is opened
// once it answers.
TEST_F(UiTest, FileDialogRunsWhileTheWindowKeepsDrawing) {
  std::mutex mutex;
  std::condition_variable cv;
  bool answer_now = false;
  bool asked = false;
  state_.flow.native_dialogs = true;
  const fs::path chosen = kProjects / "cornell_box.glint";
  state_.flow.dialog_runner = [&](const FileDialogRequest& r) -> std::optional<std::string> {
    std::unique_lock lock(mutex);
    asked = !r.save;
    // A dialog on the UI thread would hold the frame here: the wait ends after a while then.
    cv.wait_for(lock, std::chrono::seconds(3), [&] { return answer_now; });
    return chosen.string();
  };
  state_.viewport.resolution = ViewportResolution::quarter;
  request_action(doc_, state_, DocAction::open_dialog);
  frame();
  ASSERT_TRUE(state_.flow.dialog.running());
  const int64_t spp = state_.viewport.frame.stats.spp;
  const Selection before = doc_.selection;
  const int sphere = visible_sphere();
  ASSERT_GE(sphere, 0);
  click(screen(doc_.scene.spheres[sphere].center));  // blocked by the modal
  press(GLFW_KEY_N, /*ctrl=*/true);                  // so is a shortcut
  for (int i = 0; i < 5; ++i) frame();
  EXPECT_GT(state_.viewport.frame.stats.spp, spp);  // still drawing and tracing
  EXPECT_EQ(doc_.selection, before);
  EXPECT_EQ(doc_.path().filename(), "default.glint");
  const ImGuiWindow* wait = ImGui::FindWindowByName("File dialog");
  EXPECT_TRUE(wait && wait->Active) << "no modal while the dialog is open";
  {
    std::lock_guard lock(mutex);
    answer_now = true;
  }
  cv.notify_all();
  for (int i = 0; i < 200 && state_.flow.dialog.running(); ++i) frame();
  frame();
  EXPECT_TRUE(asked);
  EXPECT_FALSE(state_.flow.dialog.running());
  EXPECT_EQ(doc_.path().filename(), "cornell_box.glint");
  frame();
  EXPECT_FALSE(wait && wait->Active);
}

// Before the viewport renderer exists (it compiles its programs first), the window says so:
// "Compiling shaders..." in the status line, not a "0x0" of figures, and in the viewport.
TEST_F(UiTest, StartSaysShadersAreCompilingUntilTheFirstImage) {
  destroy_ui_context();
  start_imgui();
  state_.viewport.frame = ViewportFrame{};
  for (int i = 0; i < 2; ++i) {
    ImGui::NewFrame();
    editor_frame_before_viewport(doc_, state_);
    test::settle_test_textures();
  }
  const std::string text = status_text();
  EXPECT_NE(text.find("Compiling shaders..."), std::string::npos) << text;
  EXPECT_EQ(text.find("0x0"), std::string::npos) << text;
  // The viewport's draw list has the words: glyph quads of the text's colour around its middle.
  const ImGuiWindow* w = ImGui::FindWindowByName(kViewportWindow);
  ASSERT_NE(w, nullptr);
  const ImVec2 mid(state_.viewport.pos.x + state_.viewport.size.x / 2, state_.viewport.pos.y + state_.viewport.size.y / 2);
  int glyph_vertices = 0;
  for (const ImDrawVert& v : w->DrawList->VtxBuffer)
    if (v.col == IM_COL32(230, 230, 230, 255) && std::abs(v.pos.x - mid.x) < 150 && std::abs(v.pos.y - mid.y) < 20)
      ++glyph_vertices;
  EXPECT_GE(glyph_vertices, 4 * 15);
  frame();  // the first image
  EXPECT_EQ(status_text().find("Compiling shaders"), std::string::npos) << status_text();
}

// The status line on a narrow window: the least important figures go first, a long message is
// cut short, and nothing runs off the window.
TEST_F(UiTest, StatusLineFitsTheWindow) {
  ImGui::GetIO().DisplaySize = ImVec2(520, 400);
  show_message(state_, "Opened /a/rather/long/path/to/some/project/folder/with/a/long/name/scene.glint");
  frame();
  frame();
  const float width = 500;
  ImGui::NewFrame();
  const std::vector<StatusPiece> all = status_line(state_, ImGui::GetTime());
  const std::vector<StatusPiece> fitted = fit_status_line(all, width);
  float used = 0;
  for (const StatusPiece& p : fitted) used += ImGui::CalcTextSize(p.text.c_str()).x;
  ImGui::EndFrame();
  EXPECT_LE(used, width);
  ASSERT_FALSE(fitted.empty());
  EXPECT_NE(fitted.front().text.find(" spp"), std::string::npos) << fitted.front().text;  // kept first
  EXPECT_NE(fitted.back().text.find("Opened /a/"), std::string::npos);  // the message, cut short
  EXPECT_NE(fitted.back().text.find("..."), std::string::npos);
  EXPECT_LT(fitted.size(), all.size());
  for (const StatusPiece& p : fitted) EXPECT_EQ(p.text.find("llvmpipe"), std::string::npos);  // the renderer went
  // The bar drawn by the panels: its content no wider than the window.
  frame();
  const ImGuiWindow* bar = ImGui::FindWindowByName("##status");
  ASSERT_NE(bar, nullptr);
  EXPECT_LE(bar->ContentSize.x, bar->Size.x);
}

// "Viewport aspect" in the export dialog frames what the viewport shows: a point at the
// viewport's edge (outside the film's frame) lands at the same place in the export.
TEST_F(UiTest, ViewportAspectExportFramesTheWholeViewport) {
  doc_.scene.film = {960, 540};
  ImGui::GetIO().DisplaySize = ImVec2(800, 700);  // a tall viewport: the film is letterboxed
  frame();
  const ViewportView& v = state_.viewport;
  ASSERT_LT(v.size.x / v.size.y, 960.0f / 540.0f);
  ExportSettings s = default_export_settings(doc_, state_);
  use_viewport_aspect(s, v);
  EXPECT_NEAR(float(s.width) / s.height, v.size.x / v.size.y, 0.01f);
  const Scene exported = export_scene(doc_.scene, s);
  const Camera shown = shown_camera(doc_.scene, {v.size.x, v.size.y});
  for (glm::vec3 p : {glm::vec3(0.3f, 0.1f, 0.2f), doc_.scene.spheres[0].center, glm::vec3(-1, 2.2f, -1)}) {
    glm::vec2 in_view, in_export;
    ASSERT_TRUE(project_to_viewport(shown, {v.size.x, v.size.y}, p, in_view));
    ASSERT_TRUE(project_to_viewport(exported.camera, {float(s.width), float(s.height)}, p, in_export));
    EXPECT_NEAR(in_view.x / v.size.x, in_export.x / s.width, 0.01f);
    EXPECT_NEAR(in_view.y / v.size.y, in_export.y / s.height, 0.01f);
  }
  // Another size (or Film size) drops the viewport's framing: the film's camera again.
  s.height += 40;
  EXPECT_EQ(export_scene(doc_.scene, s).camera.vfov_deg, doc_.scene.camera.vfov_deg);
}

// The progress bar's hover help opens below the bar, off the time left; a time-limited export
// says how many samples per pixel it reached.
TEST_F(UiTest, ExportHoverHelpLeavesTheTimeLeftAndTheResultNamesItsSamples) {
  test::TempDir dir;
  state_.export_ui.show = true;
  ExportSettings& s = state_.export_ui.settings;
  s = default_export_settings(doc_, state_);
  s.output = dir / "timed.png";
  s.width = 64;
  s.height = 36;
  s.use_time = true;
  s.seconds = 600;  // running while the mouse hovers (the first export also compiles programs)
  state_.export_ui.job = std::make_unique<ExportJob>(doc_.scene, s);
  frame();
  frame();
  ASSERT_TRUE(export_running(state_));
  const ExportUi& ui = state_.export_ui;
  mouse_to(ImVec2((ui.progress_min.x + ui.progress_max.x) / 2, (ui.progress_min.y + ui.progress_max.y) / 2));
  frame();
  frame();
  const ImGuiWindow* tip = ImGui::FindWindowByName("##Tooltip_00");
  ASSERT_TRUE(tip && tip->Active) << "no hover help on the progress bar";
  const ImRect tip_rect(tip->Pos, ImVec2(tip->Pos.x + tip->Size.x, tip->Pos.y + tip->Size.y));
  EXPECT_FALSE(tip_rect.Overlaps(ImRect(ui.time_left_min, ui.time_left_max)));
  EXPECT_GT(ui.time_left_max.x, ui.time_left_min.x);
  state_.export_ui.job->cancel();
  frame();
  s.seconds = 1.5;
  state_.export_ui.job = std::make_unique<ExportJob>(doc_.scene, s);
  for (int i = 0; i < 2000 && export_running(state_); ++i) frame();
  ASSERT_EQ(state_.export_ui.job->state(), ExportJob::State::done) << state_.export_ui.job->error();
  const std::string spp = " (" + std::to_string(state_.export_ui.job->samples()) + " spp in ";
  EXPECT_NE(state_.export_ui.message.find(spp), std::string::npos) << state_.export_ui.message;
  EXPECT_NE(status_text().find(spp), std::string::npos) << status_text();
}

}  // namespace
}  // namespace glint
