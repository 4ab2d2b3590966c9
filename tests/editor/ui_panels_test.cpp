// The properties panel, Help > Controls and the orbit, driven headlessly (the fixture:
// ui_test_fixture.h): what they show and how they answer a Blender user's input.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "editor/scene_edits.h"
#include "renderer/material_types.h"
#include "ui_test_fixture.h"

namespace glint {
namespace {

class UiPanelsTest : public test::UiTest {
 protected:
  ImVec2 viewport_centre() const {
    return ImVec2(state_.viewport.pos.x + state_.viewport.size.x * 0.5f,
                  state_.viewport.pos.y + state_.viewport.size.y * 0.5f);
  }
  // The camera's height above its target as a fraction of their distance.
  float elevation() const {
    const Camera& c = doc_.scene.camera;
    return glm::normalize(c.position - c.target).y;
  }
  // A drag with the right mouse button from the viewport's centre by (dx, dy).
  void right_drag(float dx, float dy) {
    ImGuiIO& io = ImGui::GetIO();
    const ImVec2 c = viewport_centre();
    mouse_to(c);
    frame();
    io.AddMouseButtonEvent(ImGuiMouseButton_Right, true);
    frame();
    for (int i = 1; i <= 4; ++i) {
      mouse_to(ImVec2(c.x + dx * i / 4, c.y + dy * i / 4));
      frame();
    }
    io.AddMouseButtonEvent(ImGuiMouseButton_Right, false);
    frame();
  }
  // The ID of component `n` of the properties panel's DragFloat3 `label` (ImGui's DragScalarN
  // pushes the label, then the component's index, and gives the field an empty label).
  ImGuiID component_id(const char* label, int n) {
    ImGuiWindow* w = ImGui::FindWindowByName("Properties");
    return ImHashStr("", 0, ImHashData(&n, sizeof n, w->GetID(label)));
  }
  // What the field shows when typing starts in it (its value as text), then Escape.
  std::string shown_text(const char* label, int n) {
    ImGuiWindow* w = ImGui::FindWindowByName("Properties");
    const float item = w->Size.x - 2 * ImGui::GetStyle().WindowPadding.x - 110;
    const ImVec2 at = find_item("Properties", component_id(label, n), ImGui::GetStyle().WindowPadding.x + item * (n + 0.5f) / 3);
    EXPECT_GE(at.x, 0) << label << "[" << n << "] not found";
    click(at);
    frame();
    const ImGuiInputTextState& s = ImGui::GetCurrentContext()->InputTextState;
    std::string text = ImGui::GetIO().WantTextInput ? std::string(s.TextA.Data, s.TextLen) : "(not typing)";
    press(GLFW_KEY_ESCAPE);
    return text;
  }
};

// Help > Controls lists every control (right-drag orbit, Shift+D, typing into fields, Escape)
// and is wide enough for each row's text.
TEST_F(UiPanelsTest, HelpControlsListsEveryControlAndFitsItsText) {
  ImGui::GetIO().DisplaySize = ImVec2(1280, 900);
  std::string all;
  for (const ControlLine& c : editor_controls()) all += std::string(c.input) + " | " + c.action + "\n";
  for (const char* wanted : {"right drag", "Shift+D", "Click a number field", "Escape", "Middle drag", "Mouse wheel",
                             "W A S D", "Ctrl+click", "File > Examples", "Del"})
    EXPECT_NE(all.find(wanted), std::string::npos) << wanted << " missing from\n" << all;
  state_.show_controls = true;
  for (int i = 0; i < 3; ++i) frame();
  const ImGuiWindow* w = ImGui::FindWindowByName("Controls");
  ASSERT_NE(w, nullptr);
  const ImGuiStyle& style = ImGui::GetStyle();
  for (const ControlLine& c : editor_controls()) {
    const float row = ImGui::CalcTextSize(c.input).x + ImGui::CalcTextSize(c.action).x +
                      2 * style.WindowPadding.x + 4 * style.CellPadding.x;
    EXPECT_LE(row, w->Size.x) << c.input << " | " << c.action;
  }
}

// Vertical orbit as in Blender by default (a drag up moves the camera down, as if the scene were
// grabbed); the setting turns it the other way. Horizontal orbit is the same either way.
TEST_F(UiPanelsTest, VerticalOrbitFollowsBlenderUnlessInverted) {
  EXPECT_FALSE(state_.settings.invert_vertical_orbit);
  float before = elevation();
  right_drag(0, -40);  // up
  EXPECT_LT(elevation(), before - 0.05f);
  state_.settings.invert_vertical_orbit = true;
  before = elevation();
  right_drag(0, -40);
  EXPECT_GT(elevation(), before + 0.05f);
}

// A new quad starts at whole quarter turns; an angle typed into Rotation stays as typed (not
// another triple of the same orientation), and the gizmo turns it on from there.
TEST_F(UiPanelsTest, QuadRotationShowsTheTypedEulerAngles) {
  const int q = add_quad(doc_.scene);
  doc_.selection = {SelectionKind::quad, q};
  frame();
  frame();
  EXPECT_EQ(shown_text("Rotation", 0), "180.0");
  EXPECT_EQ(shown_text("Rotation", 1), "0.0");
  // Y = 100: the same orientation is also (0, 80, 180), which must not replace it.
  const ImGuiID y = component_id("Rotation", 1);
  ImGuiWindow* w = ImGui::FindWindowByName("Properties");
  const float item = w->Size.x - 2 * ImGui::GetStyle().WindowPadding.x - 110;
  click(find_item("Properties", y, ImGui::GetStyle().WindowPadding.x + item * 0.5f));
  frame();
  ASSERT_TRUE(ImGui::GetIO().WantTextInput);
  type("100");
  press(GLFW_KEY_ENTER);
  for (int i = 0; i < 3; ++i) frame();
  EXPECT_EQ(shown_text("Rotation", 0), "180.0");
  EXPECT_EQ(shown_text("Rotation", 1), "100.0");
  EXPECT_EQ(shown_text("Rotation", 2), "0.0");
}

// An emitting-capable material with no emission still shows its emission colour (0 to 1) and a
// Strength field; a strength typed there sets emission = colour x strength, above 1.
TEST_F(UiPanelsTest, EmissionShowsColourAndStrengthAlways) {
  int m = -1;
  for (size_t i = 0; i < doc_.scene.materials.size() && m < 0; ++i)
    if (uses_field(doc_.scene.materials[i].type, kFieldEmission) && doc_.scene.materials[i].emission == glm::vec3(0))
      m = int(i);
  ASSERT_GE(m, 0);
  doc_.selection = {SelectionKind::material, m};
  frame();
  frame();
  const ImVec2 at = find_item("Properties", "Strength");
  ASSERT_GE(at.x, 0) << "no Strength field for a material that does not emit yet";
  click(at);
  frame();
  ASSERT_TRUE(ImGui::GetIO().WantTextInput);
  type("5");
  press(GLFW_KEY_ENTER);
  frame();
  EXPECT_EQ(doc_.scene.materials[m].emission, glm::vec3(5));  // white by default, times 5
}

}  // namespace
}  // namespace glint
