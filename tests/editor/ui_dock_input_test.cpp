// The Dear ImGui upgrade's promises, driven headlessly as tests/editor/ui_test.cpp does: queued
// key events (no lost taps), the dock layout and its saved file, and sizes that follow the
// content scale.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE  // key codes only; GL comes from epoxy
#include <GLFW/glfw3.h>
#include <imgui_internal.h>  // FindWindowByName: where the docked panels are
#include <implot.h>

#include "editor/editor_frame.h"
#include "editor/scene_edits.h"
#include "editor/ui.h"
#include "editor/ui_layout.h"
#include "editor/viewport_renderer.h"
#include "editor_test_util.h"
#include "renderer/gl_context.h"
#include "ui_test_context.h"

namespace glint {
namespace {
namespace fs = std::filesystem;

const fs::path kProjects = fs::path(GLINT_SOURCE_DIR) / "projects";

class UiDockInputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    gl_ = HeadlessGLContext::create();
    viewport_ = std::make_unique<ViewportRenderer>();
    state_.viewport.resolution = ViewportResolution::quarter;  // tiny GL images
    state_.flow.projects_dir = kProjects;
  }
  void TearDown() override {
    state_.thumbnails.clear();
    viewport_.reset();
    if (ImGui::GetCurrentContext()) destroy_ui_context();
  }
  // A fresh UI at `scale` on a display of `display` pixels, the default project open.
  void start(float scale, ImVec2 display, const fs::path& layout = {}) {
    test::start_test_ui(scale, display);
    state_.content_scale = scale;
    if (!layout.empty()) {
      std::string error;
      load_layout(layout, error);
      EXPECT_EQ(error, "");
    }
    ASSERT_TRUE(open_document(doc_, state_, kProjects / "default.glint"));
    frame();
    frame();
  }
  void frame() {
    ImGui::NewFrame();
    editor_frame(doc_, state_, *viewport_);
    test::settle_test_textures();
  }
  const ImGuiWindow& window(const char* name) {
    const ImGuiWindow* w = ImGui::FindWindowByName(name);
    if (!w) throw std::runtime_error(std::string("no window named ") + name);  // fails the test
    return *w;
  }

  std::unique_ptr<HeadlessGLContext> gl_;
  std::unique_ptr<ViewportRenderer> viewport_;
  Document doc_;
  EditorState state_;
};

// Three Ctrl+Z taps that all come and go before the next frame starts (a slow frame): each is a
// queued press and release, so all three undo. (Undo, not Delete: after a delete nothing is
// selected, so only the first of three Delete taps could remove anything.)
TEST_F(UiDockInputTest, ThreeUndoTapsWithinOneSlowFrameUndoThreeSteps) {
  start(1, ImVec2(800, 500));
  const size_t n = doc_.scene.spheres.size();
  for (int step = 0; step < 3; ++step) {
    add_sphere(doc_.scene);
    frame();  // the frame's end makes the edit an undo step
  }
  ASSERT_EQ(doc_.scene.spheres.size(), n + 3);
  ImGuiIO& io = ImGui::GetIO();
  const ImGuiKey z = test::glfw_key(GLFW_KEY_Z);
  ASSERT_EQ(z, ImGuiKey_Z);
  io.AddKeyEvent(ImGuiMod_Ctrl, true);
  for (int tap = 0; tap < 3; ++tap) {
    io.AddKeyEvent(z, true);
    io.AddKeyEvent(z, false);
  }
  io.AddKeyEvent(ImGuiMod_Ctrl, false);
  // ImGui hands queued events out over the next frames, one press or release of a key a frame.
  for (int i = 0; i < 10; ++i) frame();
  EXPECT_EQ(doc_.scene.spheres.size(), n);
}

// The default layout: the panels are docked in one dock space, outliner left of the viewport,
// properties right of it, render statistics below it; nothing goes to the working directory.
TEST_F(UiDockInputTest, DefaultLayoutDocksThePanels) {
  start(1, ImVec2(1200, 700));
  EXPECT_EQ(ImGui::GetIO().IniFilename, nullptr);
  const ImGuiWindow& outliner = window(kOutlinerWindow);
  const ImGuiWindow& properties = window(kPropertiesWindow);
  const ImGuiWindow& stats = window(kStatsWindow);
  const ImGuiWindow& view = window(kViewportWindow);
  for (const ImGuiWindow* w : {&outliner, &properties, &stats, &view}) {
    ASSERT_NE(w->DockNode, nullptr) << w->Name;
    EXPECT_EQ(ImGui::DockNodeGetRootNode(w->DockNode), ImGui::DockNodeGetRootNode(view.DockNode)) << w->Name;
  }
  EXPECT_TRUE(view.DockNode->IsCentralNode());
  EXPECT_NEAR(outliner.Size.x, kOutlinerWidth, 1.0f);
  EXPECT_NEAR(properties.Size.x, kPropertiesWidth, 1.0f);
  EXPECT_LE(outliner.Pos.x + outliner.Size.x, view.Pos.x + 0.5f);
  EXPECT_GE(properties.Pos.x + 0.5f, view.Pos.x + view.Size.x);
  EXPECT_GE(stats.Pos.y + 0.5f, view.Pos.y + view.Size.y);
  EXPECT_NEAR(state_.viewport.pos.x, view.Pos.x, 0.5f);
}

// The layout is saved in the config folder given and restored from it: a layout saved on a wide
// window keeps its outliner width on a narrow one, where the default layout would cap it.
TEST_F(UiDockInputTest, LayoutIsSavedToAndLoadedFromTheConfigFolder) {
  test::TempDir config;
  const fs::path file = layout_file_path(config.path());
  EXPECT_EQ(file, config.path() / "layout.ini");
  start(1, ImVec2(1600, 900));
  std::string error;
  ASSERT_TRUE(save_layout_if_needed(file, /*force=*/true, error)) << error;
  std::stringstream text;
  text << std::ifstream(file).rdbuf();
  EXPECT_NE(text.str().find("[Docking]"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("[Window][Outliner]"), std::string::npos) << text.str();
  destroy_ui_context();

  start(1, ImVec2(800, 500));  // the default layout on a narrow window: the cap, 30% of 800
  EXPECT_NEAR(window(kOutlinerWindow).Size.x, 800 * 0.3f, 2.0f);  // to the splitter's whole pixel
  destroy_ui_context();

  start(1, ImVec2(800, 500), file);
  EXPECT_NEAR(window(kOutlinerWindow).Size.x, kOutlinerWidth, 1.0f);
  EXPECT_NE(window(kViewportWindow).DockNode, nullptr);
}

// Content scale 2 on a display of twice the pixels: text, widgets, panels and the plots' sizes
// are all twice the size, and the font is rasterised at that size (sharp), not stretched.
TEST_F(UiDockInputTest, PanelsAndTextScaleWithTheContentScale) {
  struct Sizes {
    float font, frame, outliner, properties, stats_h, text_w, baked;
    ImPlotStyle plot;
  };
  auto measure = [&](float scale) {
    start(scale, ImVec2(1200 * scale, 700 * scale));
    ImGui::NewFrame();  // fonts and text sizes are asked within a frame
    Sizes s{ImGui::GetFontSize(), ImGui::GetFrameHeight(), window(kOutlinerWindow).Size.x,
            window(kPropertiesWindow).Size.x, window(kStatsWindow).Size.y, ImGui::CalcTextSize("Add sphere").x,
            ImGui::GetFontBaked()->Size, ImPlot::GetStyle()};
    ImGui::EndFrame();
    destroy_ui_context();
    return s;
  };
  const Sizes one = measure(1), two = measure(2);
  EXPECT_FLOAT_EQ(two.font, 2 * one.font);
  EXPECT_NEAR(two.frame, 2 * one.frame, 1.0f);
  EXPECT_NEAR(two.outliner, 2 * one.outliner, 1.0f);
  EXPECT_NEAR(two.properties, 2 * one.properties, 1.0f);
  EXPECT_NEAR(two.stats_h, 2 * one.stats_h, 1.0f);
  EXPECT_NEAR(two.text_w, 2 * one.text_w, 0.05f * two.text_w);  // hinting may differ by a pixel
  // ImPlot's own sizes follow: its paddings, tick lengths and line sizes.
  EXPECT_FLOAT_EQ(one.plot.PlotPadding.x, ImPlotStyle().PlotPadding.x);
  EXPECT_FLOAT_EQ(two.plot.PlotPadding.x, 2 * one.plot.PlotPadding.x);
  EXPECT_FLOAT_EQ(two.plot.PlotPadding.y, 2 * one.plot.PlotPadding.y);
  EXPECT_FLOAT_EQ(two.plot.LabelPadding.x, 2 * one.plot.LabelPadding.x);
  EXPECT_FLOAT_EQ(two.plot.LegendPadding.x, 2 * one.plot.LegendPadding.x);
  EXPECT_FLOAT_EQ(two.plot.LegendInnerPadding.y, 2 * one.plot.LegendInnerPadding.y);
  EXPECT_FLOAT_EQ(two.plot.MajorTickLen.x, 2 * one.plot.MajorTickLen.x);
  EXPECT_FLOAT_EQ(two.plot.MajorGridSize.x, 2 * one.plot.MajorGridSize.x);
  EXPECT_FLOAT_EQ(two.plot.PlotBorderSize, 2 * one.plot.PlotBorderSize);
  EXPECT_FLOAT_EQ(two.plot.PlotMinSize.y, 2 * one.plot.PlotMinSize.y);
  EXPECT_FLOAT_EQ(two.plot.MinorAlpha, one.plot.MinorAlpha);  // an alpha, not a size
  EXPECT_FLOAT_EQ(one.baked, one.font);
  EXPECT_FLOAT_EQ(two.baked, two.font);
}

}  // namespace
}  // namespace glint
