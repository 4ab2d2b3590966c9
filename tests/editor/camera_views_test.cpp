// Camera views (editor/camera_views.h): the edits on plain scenes, and the properties panel's
// Views driven with the mouse: saving keeps the render going, a recall is one undo step.
#include <gtest/gtest.h>

#include "editor/camera_control.h"
#include "editor/camera_views.h"
#include "editor/ui_layout.h"
#include "ui_test_fixture.h"

namespace glint {
namespace {

using test::UiTest;

TEST(CameraViews, SaveRecallRenameDelete) {
  Scene s = new_scene();
  const Camera first = s.camera;
  EXPECT_EQ(save_view(s), 0);
  EXPECT_EQ(save_view(s, "View"), 1);
  EXPECT_EQ(s.views[0].name, "View");
  EXPECT_EQ(s.views[1].name, "View 2");  // unique
  orbit(s.camera, 0.5f, 0.2f);
  const Camera second = s.camera;
  ASSERT_NE(second, first);
  EXPECT_TRUE(update_view(s, 1));
  EXPECT_TRUE(recall_view(s, 0));
  EXPECT_EQ(s.camera, first);
  EXPECT_TRUE(recall_view(s, 1));
  EXPECT_EQ(s.camera, second);
  EXPECT_FALSE(recall_view(s, 2));
  EXPECT_FALSE(recall_view(s, -1));
  EXPECT_FALSE(rename_view(s, 0, "View 2"));  // taken
  EXPECT_FALSE(rename_view(s, 0, ""));
  EXPECT_TRUE(rename_view(s, 0, "Front"));
  EXPECT_TRUE(rename_view(s, 0, "Front"));  // its own name
  EXPECT_TRUE(delete_view(s, 0));
  ASSERT_EQ(s.views.size(), 1u);
  EXPECT_EQ(s.views[0].name, "View 2");
  EXPECT_FALSE(delete_view(s, 1));
}

// A recall right after camera moves is a step of its own: undo goes back to the moved camera,
// not past the moves.
TEST(CameraViews, RecallIsOneUndoStepAfterCameraMoves) {
  Document doc;
  const Camera start = doc.scene.camera;
  save_view(doc.scene, "Start");
  doc.end_frame(false);
  orbit(doc.scene.camera, 0.3f, 0);
  doc.end_frame(false, true);
  orbit(doc.scene.camera, 0.3f, 0);
  doc.end_frame(false, true);  // one navigation run of two orbits
  const Camera moved = doc.scene.camera;
  ASSERT_TRUE(recall_view(doc, 0));
  doc.end_frame(false);
  EXPECT_EQ(doc.scene.camera, start);
  doc.undo();
  EXPECT_EQ(doc.scene.camera, moved);
  doc.undo();
  EXPECT_EQ(doc.scene.camera, start);
  EXPECT_EQ(doc.scene.views.size(), 1u);
  doc.undo();
  EXPECT_TRUE(doc.scene.views.empty());
}

class CameraViewsUiTest : public UiTest {
 protected:
  // The centre of the Properties panel's widget `label` (found by hovering down the panel).
  ImVec2 find_in_properties(const std::string& label) {
    ImGuiWindow* w = ImGui::FindWindowByName(kPropertiesWindow);
    if (!w) return ImVec2(-1, -1);
    const ImGuiID id = w->GetID(label.c_str());
    for (float x : {w->Pos.x + 14, w->Pos.x + 40, w->Pos.x + 70})
      for (float y = w->Pos.y + 4; y < w->Pos.y + w->Size.y; y += 5) {
        mouse_to(ImVec2(x, y));
        frame();
        if (ImGui::GetCurrentContext()->HoveredId == id) return ImVec2(x, y);
      }
    return ImVec2(-1, -1);
  }
  // The same along the row at height y (the small buttons beside a view's Go).
  ImVec2 find_in_row(const std::string& label, float y) {
    ImGuiWindow* w = ImGui::FindWindowByName(kPropertiesWindow);
    if (!w) return ImVec2(-1, -1);
    const ImGuiID id = w->GetID(label.c_str());
    for (float x = w->Pos.x + 4; x < w->Pos.x + w->Size.x; x += 4) {
      mouse_to(ImVec2(x, y));
      frame();
      if (ImGui::GetCurrentContext()->HoveredId == id) return ImVec2(x, y);
    }
    return ImVec2(-1, -1);
  }
};

TEST_F(CameraViewsUiTest, SaveKeepsTheRenderRecallIsUndoable) {
  ImGui::GetIO().DisplaySize = ImVec2(1000, 800);
  doc_.selection = {SelectionKind::camera, -1};
  frame();
  frame();
  const ImVec2 save = find_in_properties("Save view##camera views");
  ASSERT_GE(save.x, 0) << "no Save view button";
  const Camera start = doc_.scene.camera;
  for (int i = 0; i < 3; ++i) frame();
  const int64_t spp_before = viewport_->renderer().sample_count();
  ASSERT_GT(spp_before, 0);
  click(save);
  ASSERT_EQ(doc_.scene.views.size(), 1u);
  EXPECT_EQ(doc_.scene.views[0].camera, start);
  EXPECT_TRUE(doc_.dirty());  // saved with the project
  // Bookmarks are in no digest: the accumulation went on through the save.
  EXPECT_GT(viewport_->renderer().sample_count(), spp_before);

  orbit(doc_.scene.camera, 0.4f, 0.1f);
  frame();
  const Camera moved = doc_.scene.camera;
  const ImVec2 go = find_in_properties(view_widget_id("Go", 0));
  ASSERT_GE(go.x, 0) << "no Go button for view 0";
  click(go);
  EXPECT_EQ(doc_.scene.camera, start);
  press(GLFW_KEY_Z, /*ctrl=*/true);
  EXPECT_EQ(doc_.scene.camera, moved);
  EXPECT_EQ(doc_.scene.views.size(), 1u);

  const ImVec2 remove = find_in_row(view_widget_id("X", 0), go.y);
  ASSERT_GE(remove.x, 0) << "no delete button for view 0";
  click(remove);
  EXPECT_TRUE(doc_.scene.views.empty());
}

}  // namespace
}  // namespace glint
