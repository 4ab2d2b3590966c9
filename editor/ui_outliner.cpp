// The outliner: spheres, quads, materials and textures; select, rename, duplicate, delete.
#include <cstdio>

#include "editor/scene_edits.h"
#include "editor/ui.h"
#include "editor/ui_context.h"
#include "editor/ui_tip.h"

namespace glint {
namespace {

// One selectable row with a context menu and inline renaming (double-click or the menu).
void row(Document& doc, EditorState& state, Selection item, const std::string& name, const char* suffix = "") {
  ImGui::PushID(static_cast<int>(item.kind) * 100000 + item.index);
  if (state.renaming.item == item) {
    ImGui::SetNextItemWidth(-1);
    if (ImGui::IsWindowAppearing() || !ImGui::IsAnyItemActive()) ImGui::SetKeyboardFocusHere();
    bool done = ImGui::InputText("##rename", state.renaming.buffer, sizeof state.renaming.buffer,
                                 ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_AutoSelectAll);
    if (done) {
      if (!rename(doc.scene, item, state.renaming.buffer))
        show_message(state, std::string("The name '") + state.renaming.buffer + "' is empty or taken");
      state.renaming.item = {};
    } else if (ImGui::IsItemDeactivated() || ImGui::IsKeyPressed(ImGuiKey_Escape)) {
      state.renaming.item = {};
    }
  } else {
    std::string label = name + suffix;
    if (ImGui::Selectable(label.c_str(), doc.selection == item, ImGuiSelectableFlags_AllowDoubleClick)) {
      doc.selection = item;
      if (ImGui::IsMouseDoubleClicked(0)) {
        state.renaming.item = item;
        std::snprintf(state.renaming.buffer, sizeof state.renaming.buffer, "%s", name.c_str());
      }
    }
    // After a moment's rest: a list is passed over often. The camera and the environment
    // cannot be renamed, duplicated or deleted.
    const bool fixed = item.kind == SelectionKind::camera || item.kind == SelectionKind::environment;
    resting_tip(fixed ? "Click to edit it in Properties."
                      : "Click to select, double-click to rename; right-click to rename, duplicate or delete.");
    if (!fixed && ImGui::BeginPopupContextItem()) {
      doc.selection = item;
      if (ImGui::MenuItem("Rename")) {
        state.renaming.item = item;
        std::snprintf(state.renaming.buffer, sizeof state.renaming.buffer, "%s", name.c_str());
      }
      if (ImGui::MenuItem("Duplicate")) doc.selection = {item.kind, duplicate(doc.scene, item)};
      if (ImGui::MenuItem("Delete")) delete_item(doc, state, item);
      ImGui::EndPopup();
    }
  }
  ImGui::PopID();
}

bool section(const char* label, int count) {
  char header[64];
  std::snprintf(header, sizeof header, "%s (%d)###%s", label, count, label);
  const bool open = ImGui::CollapsingHeader(header, ImGuiTreeNodeFlags_DefaultOpen);
  resting_tip("Click to fold or unfold the list.");
  return open;
}

}  // namespace

void draw_outliner(Document& doc, EditorState& state) {
  Scene& s = doc.scene;
  // Buttons first: they stay visible however long the lists grow.
  float w = (ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x) * 0.5f;
  if (ImGui::Button("Add sphere", ImVec2(w, 0))) doc.selection = {SelectionKind::sphere, add_sphere(s)};
  tip("A new sphere in front of the camera, at the focus distance (selected).");
  ImGui::SameLine();
  if (ImGui::Button("Add quad", ImVec2(w, 0))) doc.selection = {SelectionKind::quad, add_quad(s)};
  tip("A new quad facing the camera, at the focus distance (selected).");
  bool object = doc.selection.kind == SelectionKind::sphere || doc.selection.kind == SelectionKind::quad ||
                doc.selection.kind == SelectionKind::material || doc.selection.kind == SelectionKind::texture;
  ImGui::BeginDisabled(!object);
  if (ImGui::Button("Duplicate", ImVec2(w, 0))) doc.selection = {doc.selection.kind, duplicate(s, doc.selection)};
  tip("A copy of the selected object, material or texture under a new name (an object a little\n"
      "to the side).");
  ImGui::SameLine();
  if (ImGui::Button("Delete", ImVec2(w, 0))) delete_item(doc, state, doc.selection);
  tip("Delete the selected object, material or texture (Del); a material that objects use asks\n"
      "first.");
  ImGui::EndDisabled();
  ImGui::Separator();

  ImGui::BeginChild("tree");
  row(doc, state, {SelectionKind::camera, -1}, "Camera");
  row(doc, state, {SelectionKind::environment, -1}, "Environment");
  if (section("Spheres", int(s.spheres.size())))
    for (int i = 0; i < int(s.spheres.size()); ++i) row(doc, state, {SelectionKind::sphere, i}, s.spheres[i].name);
  if (section("Quads", int(s.quads.size())))
    for (int i = 0; i < int(s.quads.size()); ++i) row(doc, state, {SelectionKind::quad, i}, s.quads[i].name);
  if (section("Materials", int(s.materials.size()))) {
    for (int i = 0; i < int(s.materials.size()); ++i) {
      std::string suffix = std::string("  (") + to_string(s.materials[i].type) + ")";
      row(doc, state, {SelectionKind::material, i}, s.materials[i].name, suffix.c_str());
    }
    if (ImGui::SmallButton("+ material")) doc.selection = {SelectionKind::material, add_material(s, MaterialType::matte)};
    tip("A new grey matte material (selected; Add > Material for other types).");
  }
  if (section("Textures", int(s.textures.size()))) {
    for (int i = 0; i < int(s.textures.size()); ++i) {
      unsigned thumb = state.thumbnails.get(resolve_asset_path(s, s.textures[i].path), 64);
      if (thumb) {
        ImGui::Image(static_cast<ImTextureID>(thumb), ImVec2(ui_units(18), ui_units(18)));
        ImGui::SameLine();
      }
      row(doc, state, {SelectionKind::texture, i}, s.textures[i].name);
    }
    if (ImGui::SmallButton("+ texture from file")) choose_file(doc, state, FilePurpose::add_texture);
    tip("Add an image file as a texture (or drop it on the window over a selected object).");
  }
  ImGui::EndChild();
}

}  // namespace glint
