// Hover help and layout of the panels, driven with the simulated mouse (the fixture:
// ui_test_fixture.h): every item of the export dialog and the outliner explains itself in a
// tooltip, and the Exposure field's value is not covered by a slider's grab.
#include <gtest/gtest.h>

#include <cstdio>
#include <set>

#include "editor/ui_layout.h"
#include "tests/temp_dir.h"
#include "ui_test_fixture.h"

namespace glint {
namespace {

class UiTooltipTest : public test::UiTest {
 protected:
  bool tooltip_shown() {
    const ImGuiWindow* w = ImGui::FindWindowByName("##Tooltip_00");
    return w && w->Active;
  }
  // Rests the mouse on every item of a window's content (a grid of points `step_x` by `step_y`
  // apart) and returns the items that showed no tooltip within `wait_frames` frames at rest, as
  // "x,y" positions in the window; each item is checked once, scroll bars are not items.
  std::vector<std::string> items_without_tooltip(const char* window, float step_x, float step_y, int wait_frames) {
    std::vector<std::string> missing;
    std::set<ImGuiID> checked;
    items_checked_ = 0;
    const ImGuiWindow* w = ImGui::FindWindowByName(window);
    EXPECT_NE(w, nullptr) << window;
    if (!w) return {"no window"};
    const ImRect inner = w->InnerRect;  // below the title bar or the dock tab
    for (float y = inner.Min.y + 2; y < inner.Max.y - 2; y += step_y)
      for (float x = inner.Min.x + 4; x < inner.Max.x - 4; x += step_x) {
        mouse_to(ImVec2(x, y));
        frame();
        const ImGuiContext& g = *ImGui::GetCurrentContext();
        const ImGuiID id = g.HoveredId;
        if (id == 0 || !checked.insert(id).second) continue;
        if (g.HoveredWindow && (id == ImGui::GetWindowScrollbarID(g.HoveredWindow, ImGuiAxis_X) ||
                                id == ImGui::GetWindowScrollbarID(g.HoveredWindow, ImGuiAxis_Y)))
          continue;
        ++items_checked_;
        bool shown = tooltip_shown();
        for (int i = 0; i < wait_frames && !shown; ++i) {
          frame();
          shown = tooltip_shown();
        }
        if (!shown) missing.push_back(std::to_string(int(x - w->Pos.x)) + "," + std::to_string(int(y - w->Pos.y)));
      }
    return missing;
  }
  int items_checked_ = 0;  // by the last items_without_tooltip
};

TEST_F(UiTooltipTest, EveryItemOfTheExportDialogHasATooltip) {
  test::TempDir dir;
  state_.export_ui.show = true;
  state_.export_ui.settings = default_export_settings(doc_, state_);
  state_.export_ui.settings.output = dir / "shot.png";
  state_.export_ui.settings.width = 48;
  state_.export_ui.settings.height = 40;  // not the film's aspect: the warning line shows too
  frame();
  frame();
  const std::vector<std::string> missing = items_without_tooltip("Export render", 40, 6, 0);
  EXPECT_TRUE(missing.empty()) << "items without a tooltip at (window x,y): " << ::testing::PrintToString(missing);
  // Size, its two buttons, Samples, Time, Samples/pixel, Output file, Format, Choose file,
  // Denoise, Render: all found (the grid is fine enough).
  EXPECT_GE(items_checked_, 11);
  // The time budget's own field has one too.
  state_.export_ui.settings.use_time = true;
  frame();
  EXPECT_TRUE(items_without_tooltip("Export render", 40, 6, 0).empty());
}

TEST_F(UiTooltipTest, EveryItemOfTheOutlinerHasATooltipOnceTheMouseRests) {
  doc_.selection = {SelectionKind::sphere, 0};  // Duplicate and Delete enabled
  frame();
  // The rows' tooltips wait for the mouse to rest (ImGui's short delay, 0.15 s at 60 frames a second).
  const std::vector<std::string> missing = items_without_tooltip(kOutlinerWindow, 48, 6, 30);
  EXPECT_TRUE(missing.empty()) << "items without a tooltip at (window x,y): " << ::testing::PrintToString(missing);
  // The four buttons, Camera, Environment, the section headers and the rows in view.
  EXPECT_GE(items_checked_, 15);
  std::printf("outliner: %d items hovered\n", items_checked_);
}

// At 0 stops a slider's grab sat in the middle of "0.00 stops"; the field draws no grab.
TEST_F(UiTooltipTest, ExposureFieldShowsItsValueWithNoGrabOverIt) {
  doc_.selection = {SelectionKind::sphere, 0};  // a short panel: Display near its top
  frame();
  ImGuiWindow* w = ImGui::FindWindowByName(kPropertiesWindow);
  ASSERT_NE(w, nullptr);
  const ImGuiID id = w->GetID("Exposure");
  ImVec2 at(-1, -1);
  for (float y = w->Pos.y + 4; y < w->Pos.y + w->Size.y && at.x < 0; y += 6) {
    mouse_to(ImVec2(w->Pos.x + 60, y));
    frame();
    if (ImGui::GetCurrentContext()->HoveredId == id) at = ImVec2(w->Pos.x + 60, y);
  }
  ASSERT_GE(at.x, 0) << "the Exposure field was not found";
  EXPECT_TRUE(tooltip_shown());
  // A click without a move edits nothing; it makes the field the navigation item, whose
  // rectangle ImGui keeps (relative to the window's content start).
  const float exposure = doc_.scene.display.exposure;
  click(at);
  EXPECT_EQ(doc_.scene.display.exposure, exposure);
  ASSERT_EQ(ImGui::GetCurrentContext()->NavId, id);
  const ImRect rel = w->NavRectRel[0];
  const ImVec2 off = w->DC.CursorStartPos;
  const ImRect field(ImVec2(rel.Min.x + off.x, rel.Min.y + off.y), ImVec2(rel.Max.x + off.x, rel.Max.y + off.y));
  EXPECT_GT(field.GetWidth(), 50);
  const ImU32 grab = ImGui::GetColorU32(ImGuiCol_SliderGrab), grab_active = ImGui::GetColorU32(ImGuiCol_SliderGrabActive);
  int grab_vertices = 0;
  for (const ImDrawVert& v : w->DrawList->VtxBuffer)
    if ((v.col == grab || v.col == grab_active) && field.Contains(v.pos)) ++grab_vertices;
  EXPECT_EQ(grab_vertices, 0) << "a slider grab is drawn inside the Exposure field";
}

}  // namespace
}  // namespace glint
