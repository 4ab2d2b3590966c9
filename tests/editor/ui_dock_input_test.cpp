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

  start(1, ImVec2(850, 500));  // the default layout on a narrow window: the cap, 30% of 850
  EXPECT_NEAR(window(kOutlinerWindow).Size.x, 850 * 0.3f, 2.0f);  // to the splitter's whole pixel
  destroy_ui_context();

  start(1, ImVec2(850, 500), file);  // the viewport keeps over a quarter: the saved widths stay
  EXPECT_NEAR(window(kOutlinerWindow).Size.x, kOutlinerWidth, 1.0f);
  EXPECT_NE(window(kViewportWindow).DockNode, nullptr);
}

// The panels' sizes of a layout saved at one content scale, restored at `scale` on `display`.
struct PanelSizes {
  float outliner, properties, stats_h, view_w, view_h;
};

// A layout saved in a session at content scale 2 (3200x1800) and restored at scale 1 (1600x900),
// and the other way round: the panels keep their size in ImGui units (the default layout's at
// the new scale), the viewport its share of the window, the plots their room.
TEST_F(UiDockInputTest, LayoutSavedAtOneContentScaleFitsAnother) {
  auto sizes = [&] {
    return PanelSizes{window(kOutlinerWindow).Size.x, window(kPropertiesWindow).Size.x, window(kStatsWindow).Size.y,
                      state_.viewport.size.x, state_.viewport.size.y};
  };
  auto session = [&](float scale, const fs::path& load, const fs::path& save) {
    start(scale, ImVec2(1600 * scale, 900 * scale), load);
    const PanelSizes s = sizes();
    std::string error;
    if (!save.empty()) {
      EXPECT_TRUE(save_layout_if_needed(save, /*force=*/true, error)) << error;
    }
    destroy_ui_context();
    return s;
  };
  test::TempDir config;
  const fs::path at2 = config.path() / "at2.ini", at1 = config.path() / "at1.ini";
  const PanelSizes default1 = session(1, {}, at1), default2 = session(2, {}, at2);
  std::stringstream text;
  text << std::ifstream(at2).rdbuf();
  EXPECT_NE(text.str().find("[Glint][Layout]\nScale=2.000\nSize=3200,"), std::string::npos) << text.str();

  for (const auto& [restored, expected] : {std::pair{session(1, at2, {}), default1}, std::pair{session(2, at1, {}), default2}}) {
    EXPECT_NEAR(restored.outliner, expected.outliner, 2.0f);
    EXPECT_NEAR(restored.properties, expected.properties, 2.0f);
    EXPECT_NEAR(restored.stats_h, expected.stats_h, 2.0f);
    EXPECT_NEAR(restored.view_w, expected.view_w, 3.0f);
    EXPECT_NEAR(restored.view_h, expected.view_h, 3.0f);
  }
  EXPECT_NEAR(default2.outliner, 2 * default1.outliner, 2.0f);
}

// A layout whose panels leave the viewport a strip (saved on a larger window, or an older file
// without its scale): shrunk with the window where the file says its size, else rebuilt; the
// viewport keeps at least a quarter of the window either way.
TEST_F(UiDockInputTest, LayoutThatSqueezesTheViewportIsAdapted) {
  test::TempDir config;
  const fs::path file = config.path() / "wide.ini";
  start(1, ImVec2(3000, 1000));
  // Wide side panels, as a user may leave them on a large monitor.
  ImGuiDockNode* outliner = window(kOutlinerWindow).DockNode;
  ImGuiDockNode* properties = window(kPropertiesWindow).DockNode;
  outliner->SizeRef.x = 1000;
  properties->SizeRef.x = 1100;
  frame();
  frame();
  ASSERT_NEAR(window(kOutlinerWindow).Size.x, 1000, 2.0f);
  std::string error;
  ASSERT_TRUE(save_layout_if_needed(file, /*force=*/true, error)) << error;
  destroy_ui_context();

  start(1, ImVec2(1500, 800), file);  // half as wide: proportions kept
  EXPECT_NEAR(window(kOutlinerWindow).Size.x, 500, 3.0f);
  EXPECT_GE(state_.viewport.size.x, 0.25f * 1500);
  destroy_ui_context();

  // The same file without its record (an older editor's): the default layout instead.
  std::stringstream text;
  text << std::ifstream(file).rdbuf();
  std::string old = text.str();
  old.erase(old.find("[Glint][Layout]"), old.find("\n\n", old.find("[Glint][Layout]")) + 2 - old.find("[Glint][Layout]"));
  std::ofstream(file, std::ios::trunc) << old;
  start(1, ImVec2(1500, 800), file);
  EXPECT_NEAR(window(kOutlinerWindow).Size.x, kOutlinerWidth, 2.0f);
  EXPECT_NEAR(window(kPropertiesWindow).Size.x, kPropertiesWidth, 2.0f);
  EXPECT_GE(state_.viewport.size.x, 0.25f * 1500);
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
