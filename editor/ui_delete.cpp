// Deleting from the editor: a material in use asks first, naming the objects that use it.
#include <string>

#include "editor/scene_edits.h"
#include "editor/ui.h"
#include "editor/ui_context.h"

namespace glint {
namespace {

constexpr const char* kDeletePopup = "Delete material?";

}  // namespace

void delete_item(Document& doc, EditorState& state, Selection what) {
  if (what.kind == SelectionKind::material && what.index >= 0 && what.index < int(doc.scene.materials.size())) {
    auto users = material_users(doc.scene, doc.scene.materials[what.index].name);
    if (!users.empty()) {
      state.delete_prompt = {what, std::move(users), true};
      return;
    }
  }
  if (what.kind == SelectionKind::sphere || what.kind == SelectionKind::quad ||
      what.kind == SelectionKind::material || what.kind == SelectionKind::texture)
    doc.selection = remove(doc.scene, what);
}

void draw_delete_prompt(Document& doc, EditorState& state) {
  DeletePrompt& p = state.delete_prompt;
  if (p.request_open) {
    ImGui::OpenPopup(kDeletePopup);
    p.request_open = false;
  }
  if (!ImGui::BeginPopupModal(kDeletePopup, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  const bool valid = p.material.index >= 0 && p.material.index < int(doc.scene.materials.size());
  const std::string name = valid ? doc.scene.materials[p.material.index].name : std::string();
  ImGui::Text("Material '%s' is used by %d object(s):", name.c_str(), int(p.users.size()));
  const size_t shown = std::min<size_t>(p.users.size(), 8);
  for (size_t i = 0; i < shown; ++i) ImGui::BulletText("%s", p.users[i].c_str());
  if (p.users.size() > shown) ImGui::BulletText("and %d more", int(p.users.size() - shown));
  Scene preview = doc.scene;
  if (valid) preview.materials.erase(preview.materials.begin() + p.material.index);
  ImGui::Text("Deleting it gives them the neutral material '%s'.", default_material(preview).c_str());
  ImGui::Spacing();
  if (ImGui::Button("Delete", ImVec2(ui_units(120), 0))) {
    ImGui::CloseCurrentPopup();
    if (valid) doc.selection = remove(doc.scene, p.material);
    p = {};
  }
  ImGui::SameLine();
  if (ImGui::Button("Cancel", ImVec2(ui_units(120), 0)) || ImGui::IsKeyPressed(ImGuiKey_Escape)) {
    ImGui::CloseCurrentPopup();
    p = {};
  }
  ImGui::EndPopup();
}

}  // namespace glint
