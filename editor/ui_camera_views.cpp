// The camera views of the properties panel (under the camera): save the current view, recall,
// rename, update and delete named bookmarks (editor/camera_views.h). Saved with the project;
// a recall is one undo step.
#include <cstdio>

#include "editor/camera_views.h"
#include "editor/ui.h"
#include "editor/ui_context.h"
#include "editor/ui_tip.h"

namespace glint {

std::string view_widget_id(const char* what, int index) {
  return std::string(what) + "##view " + std::to_string(index);
}

void draw_camera_views(Document& doc, EditorState& state) {
  ImGui::Spacing();
  ImGui::TextColored(ImVec4(0.55f, 0.75f, 1.0f, 1.0f), "Views");
  ImGui::Separator();
  if (ImGui::Button("Save view##camera views")) {
    const int i = save_view(doc.scene);
    if (i < 0) show_message(state, "A project holds at most 1024 views");
    else show_message(state, "Saved the camera as view '" + doc.scene.views[i].name + "'");
  }
  tip("Bookmark the current camera under a name (saved with the project; the render goes on).");
  if (doc.scene.views.empty()) {
    ImGui::TextDisabled("no saved views");
    return;
  }
  int recall = -1, remove = -1, update = -1;
  for (int i = 0; i < static_cast<int>(doc.scene.views.size()); ++i) {
    const CameraView& v = doc.scene.views[i];
    if (ImGui::SmallButton(view_widget_id("Go", i).c_str())) recall = i;
    tip("Move the camera to this view (Ctrl+Z goes back).");
    ImGui::SameLine();
    if (ImGui::SmallButton(view_widget_id("Set", i).c_str())) update = i;
    tip("Store the current camera in this view.");
    ImGui::SameLine();
    if (ImGui::SmallButton(view_widget_id("X", i).c_str())) remove = i;
    tip("Delete this view.");
    ImGui::SameLine();
    char buffer[256];
    std::snprintf(buffer, sizeof buffer, "%s", v.name.c_str());
    ImGui::SetNextItemWidth(-1);
    if (ImGui::InputText(view_widget_id("", i).c_str(), buffer, sizeof buffer,
                         ImGuiInputTextFlags_EnterReturnsTrue) &&
        !rename_view(doc.scene, i, buffer))
      show_message(state, std::string("The view name '") + buffer + "' is empty or taken");
    tip("The view's name; Enter renames.");
  }
  if (recall >= 0) recall_view(doc, recall);
  if (update >= 0) update_view(doc.scene, update);
  if (remove >= 0) delete_view(doc.scene, remove);
}

}  // namespace glint
