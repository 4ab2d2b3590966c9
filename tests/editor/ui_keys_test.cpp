// Keys, fields and menus driven headlessly (the fixture: ui_test_fixture.h): a click in a number
// field types into it and keeps the keys there, single keys act on the scene only where the
// pointer is, Escape closes a menu, examples open as untitled copies, undo steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>

#include "editor/scene_edits.h"
#include "renderer/project_file.h"
#include "tests/temp_dir.h"
#include "ui_test_fixture.h"

namespace glint {
namespace {
namespace fs = std::filesystem;

class UiKeysTest : public test::UiTest {
 protected:
  ImVec2 viewport_centre() const {
    return ImVec2(state_.viewport.pos.x + state_.viewport.size.x * 0.5f,
                  state_.viewport.pos.y + state_.viewport.size.y * 0.5f);
  }
  ImVec2 over_properties() {
    const ImGuiWindow* w = ImGui::FindWindowByName("Properties");
    return ImVec2(w->Pos.x + w->Size.x * 0.5f, w->Pos.y + w->Size.y - 10);
  }
  // Clicks a number field of the properties panel and types `text` and Enter into it.
  void type_into(const char* label, const std::string& text) {
    const ImVec2 at = find_item("Properties", label);
    ASSERT_GE(at.x, 0) << label << " not found";
    click(at);
    frame();
    ASSERT_TRUE(ImGui::GetIO().WantTextInput) << "a click in " << label << " does not start typing";
    type(text);
    press(GLFW_KEY_ENTER);
  }
  // Clicks a menu of the main menu bar by its position there (0: File).
  void open_main_menu(float x_offset) {
    const ImGuiWindow* bar = ImGui::FindWindowByName("##MainMenuBar");
    ASSERT_NE(bar, nullptr);
    click(ImVec2(bar->Pos.x + x_offset, bar->Pos.y + bar->Size.y * 0.5f));
    frame();
  }
  bool any_popup_open() {
    return ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId | ImGuiPopupFlags_AnyPopupLevel);
  }
};

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A click on Radius without a drag types into it (Blender's way, at any frame rate): Delete and
// digits edit the text, not the scene; Enter sets the value. Then, with the pointer still on
// the panel, Delete deletes nothing; over the viewport it deletes the selection.
TEST_F(UiKeysTest, AClickInANumberFieldTypesAndKeepsTheKeys) {
  doc_.selection = {SelectionKind::sphere, 0};
  frame();
  const size_t spheres = doc_.scene.spheres.size();
  const fs::path path = doc_.path();
  type_into("Radius", "");  // starts typing; Enter leaves it unchanged
  const float radius = doc_.scene.spheres[0].radius;
  EXPECT_FALSE(ImGui::GetIO().WantTextInput);
  click(find_item("Properties", "Radius"));
  frame();
  ASSERT_TRUE(ImGui::GetIO().WantTextInput);
  press(GLFW_KEY_DELETE);  // deletes the selected text
  type("-1");
  EXPECT_EQ(doc_.scene.spheres.size(), spheres);
  EXPECT_EQ(doc_.path(), path);
  press(GLFW_KEY_BACKSPACE);
  press(GLFW_KEY_BACKSPACE);
  type("0.25");
  press(GLFW_KEY_ENTER);
  EXPECT_FLOAT_EQ(doc_.scene.spheres[0].radius, 0.25f);
  EXPECT_NE(radius, 0.25f);
  EXPECT_EQ(doc_.scene.spheres.size(), spheres);
  EXPECT_EQ(doc_.path(), path);

  mouse_to(over_properties());
  frame();
  press(GLFW_KEY_DELETE);
  EXPECT_EQ(doc_.scene.spheres.size(), spheres) << "Delete over a panel deleted the selection";
  mouse_to(viewport_centre());
  frame();
  press(GLFW_KEY_DELETE);
  EXPECT_EQ(doc_.scene.spheres.size(), spheres - 1);
}

// Digits are no shortcuts; W A S D Q E fly only with the pointer on the viewport.
TEST_F(UiKeysTest, SingleKeysActOnTheSceneOnlyFromTheViewport) {
  const fs::path path = doc_.path();
  mouse_to(viewport_centre());
  frame();
  for (int key = GLFW_KEY_1; key <= GLFW_KEY_9; ++key) press(key);
  EXPECT_EQ(doc_.path(), path);
  EXPECT_FALSE(unsaved_prompt_open_);
  EXPECT_FALSE(doc_.dirty());

  ImGuiIO& io = ImGui::GetIO();
  const Camera camera = doc_.scene.camera;
  mouse_to(over_properties());
  frame();
  for (ImGuiKey key : {ImGuiKey_W, ImGuiKey_A, ImGuiKey_S, ImGuiKey_D, ImGuiKey_Q, ImGuiKey_E}) {
    io.AddKeyEvent(key, true);
    for (int i = 0; i < 4; ++i) frame();
    io.AddKeyEvent(key, false);
    frame();
  }
  EXPECT_EQ(doc_.scene.camera, camera) << "a fly key moved the camera from the properties panel";
  mouse_to(viewport_centre());
  frame();
  io.AddKeyEvent(ImGuiKey_W, true);
  for (int i = 0; i < 4; ++i) frame();
  io.AddKeyEvent(ImGuiKey_W, false);
  frame();
  EXPECT_NE(doc_.scene.camera.position, camera.position);
}

// Escape closes an open menu, and the next Delete (over the viewport) deletes.
TEST_F(UiKeysTest, EscapeClosesAnOpenMenu) {
  doc_.selection = {SelectionKind::sphere, 0};
  const size_t spheres = doc_.scene.spheres.size();
  open_main_menu(14);
  ASSERT_TRUE(any_popup_open());
  press(GLFW_KEY_ESCAPE);
  EXPECT_FALSE(any_popup_open());
  mouse_to(viewport_centre());
  frame();
  press(GLFW_KEY_DELETE);
  EXPECT_EQ(doc_.scene.spheres.size(), spheres - 1);
}

// File > Examples lists every project of projects/ and opens the chosen one as an untitled copy
// whose assets resolve from projects/; Ctrl+S then asks for a path and the example stays as
// shipped. (A copy of projects/: a regression must not overwrite the source tree's examples.)
TEST_F(UiKeysTest, ExamplesMenuListsEveryProjectAndOpensUntitledCopies) {
  test::TempDir dir;
  fs::copy(test::kProjects, dir / "projects", fs::copy_options::recursive);
  state_.flow.projects_dir = dir / "projects";
  state_.flow.native_dialogs = false;
  std::vector<std::string> shipped;
  for (const fs::directory_entry& e : fs::directory_iterator(state_.flow.projects_dir))
    if (e.path().extension() == ".glint") shipped.push_back(e.path().stem().string());
  ASSERT_GE(shipped.size(), 8u);

  open_main_menu(14);
  const ImGuiWindow* file_menu = ImGui::FindWindowByName("###Menu_00");
  ASSERT_NE(file_menu, nullptr);
  const ImVec2 examples = find_item("###Menu_00", "Examples", 30);
  ASSERT_GE(examples.x, 0);
  click(examples);
  frame();
  ImGuiWindow* list = ImGui::FindWindowByName("###Menu_01");
  ASSERT_NE(list, nullptr);
  std::vector<ImGuiID> hovered;
  ImVec2 cornell(-1, -1);
  for (float y = list->Pos.y + 4; y < list->Pos.y + list->Size.y; y += 4) {
    mouse_to(ImVec2(list->Pos.x + 30, y));
    frame();
    hovered.push_back(ImGui::GetCurrentContext()->HoveredId);
    if (hovered.back() == list->GetID("cornell_box")) cornell = ImVec2(list->Pos.x + 30, y);
  }
  for (const std::string& name : shipped)
    EXPECT_NE(std::find(hovered.begin(), hovered.end(), list->GetID(name.c_str())), hovered.end())
        << name << " is not in File > Examples";

  const fs::path example = state_.flow.projects_dir / "cornell_box.glint";
  const std::string text = read_text(example);
  ASSERT_GE(cornell.x, 0);
  click(cornell);
  frame();
  EXPECT_TRUE(doc_.path().empty()) << doc_.path();
  EXPECT_EQ(doc_.scene, load_project(example));  // assets resolved from the examples' folder
  EXPECT_FALSE(doc_.dirty());
  doc_.scene.spheres[0].radius *= 1.5f;
  frame();
  press(GLFW_KEY_S, /*ctrl=*/true);
  frame();
  EXPECT_TRUE(path_prompt_open_);  // Save asks where
  press(GLFW_KEY_ESCAPE);
  EXPECT_EQ(read_text(example), text);
}

// A typed field of view, a typed aperture, a Ctrl+click focus and an orbit are undone one at a
// time; the orbit and a zoom right after it are one step.
TEST_F(UiKeysTest, DeliberateCameraSettingsAreUndoneOneByOne) {
  doc_.selection = {SelectionKind::camera, -1};
  frame();
  std::vector<Camera> cameras{doc_.scene.camera};
  type_into("Field of view", "55");
  EXPECT_FLOAT_EQ(doc_.scene.camera.vfov_deg, 55);
  cameras.push_back(doc_.scene.camera);
  type_into("Aperture", "0.05");
  EXPECT_FLOAT_EQ(doc_.scene.camera.aperture_radius, 0.05f);
  cameras.push_back(doc_.scene.camera);
  const int ball = visible_sphere();
  ASSERT_GE(ball, 0);
  click(screen(doc_.scene.spheres[ball].center), /*ctrl=*/true);
  EXPECT_NE(doc_.scene.camera.focus_distance, cameras.back().focus_distance);
  cameras.push_back(doc_.scene.camera);
  ImGuiIO& io = ImGui::GetIO();
  const ImVec2 c = viewport_centre();
  mouse_to(c);
  frame();
  io.AddMouseButtonEvent(ImGuiMouseButton_Right, true);
  frame();
  for (int i = 1; i <= 4; ++i) {
    mouse_to(ImVec2(c.x + 10 * i, c.y));
    frame();
  }
  io.AddMouseButtonEvent(ImGuiMouseButton_Right, false);
  frame();
  io.AddMouseWheelEvent(0, 1);
  frame();
  frame();
  EXPECT_NE(doc_.scene.camera.position, cameras.back().position);
  for (size_t i = cameras.size(); i-- > 0;) {
    press(GLFW_KEY_Z, /*ctrl=*/true);
    EXPECT_EQ(doc_.scene.camera, cameras[i]) << "after undo " << cameras.size() - i;
  }
}

// Shift+D duplicates the selection beside it and selects the copy; it does not fly.
TEST_F(UiKeysTest, ShiftDDuplicatesTheSelection) {
  doc_.selection = {SelectionKind::sphere, 0};
  mouse_to(viewport_centre());
  frame();
  const Sphere original = doc_.scene.spheres[0];
  const Camera camera = doc_.scene.camera;
  press(GLFW_KEY_D, false, /*shift=*/true);
  ASSERT_EQ(doc_.selection.kind, SelectionKind::sphere);
  ASSERT_EQ(doc_.selection.index, int(doc_.scene.spheres.size()) - 1);
  const Sphere& copy = doc_.scene.spheres.back();
  EXPECT_EQ(copy.radius, original.radius);
  EXPECT_GE(glm::length(copy.center - original.center), 2 * original.radius);
  EXPECT_EQ(doc_.scene.camera, camera);
}

}  // namespace
}  // namespace glint
