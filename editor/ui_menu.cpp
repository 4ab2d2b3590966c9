// The main menu bar and the keyboard shortcuts.
// Keys are Dear ImGui's named keys: the GLFW backend queues each press and release as an
// input event (io.AddKeyEvent), so a tap shorter than a slow frame is still seen.

#include <algorithm>
#include <cmath>
#include <cstring>

#include <imgui_internal.h>  // the hovered and active windows: where a key goes

#include "editor/camera_control.h"
#include "renderer/material_types.h"
#include "editor/scene_edits.h"
#include "editor/ui.h"
#include "editor/ui_layout.h"

namespace glint {
namespace {

bool key_pressed(ImGuiKey key) { return ImGui::IsKeyPressed(key, false); }

// A sphere around the selection, for "frame selection".
bool selection_bounds(const Scene& scene, Selection sel, glm::vec3& center, float& radius) {
  if (sel.kind == SelectionKind::sphere && sel.index >= 0 && sel.index < int(scene.spheres.size())) {
    center = scene.spheres[sel.index].center;
    radius = scene.spheres[sel.index].radius;
    return true;
  }
  if (sel.kind == SelectionKind::quad && sel.index >= 0 && sel.index < int(scene.quads.size())) {
    const Quad& q = scene.quads[sel.index];
    center = (q.corners[0] + q.corners[1] + q.corners[2] + q.corners[3]) * 0.25f;
    radius = 0;
    for (const glm::vec3& c : q.corners) radius = std::max(radius, glm::length(c - center));
    return true;
  }
  return false;
}

// The selection fills about 60% of the film's shorter side (frame() alone fits it exactly to
// the view height, which leaves no room around it and crops a portrait film's sides).
constexpr float kFrameMargin = 1.6f;

void frame_selection(Document& doc) {
  glm::vec3 c;
  float r;
  if (!selection_bounds(doc.scene, doc.selection, c, r)) return;
  const Film& f = doc.scene.film;
  const float aspect = float(std::max(f.width, 1)) / float(std::max(f.height, 1));
  const float h = std::tan(glm::radians(doc.scene.camera.vfov_deg) * 0.5f);
  // A portrait film's horizontal half-angle is the smaller one: fit the sphere to it.
  const float narrow = aspect < 1 ? std::atan(h * aspect) / std::atan(h) : 1.0f;
  frame(doc.scene.camera, c, r * kFrameMargin / narrow);
}

// Which single-key shortcuts may act on the scene this frame. Keys go where the pointer is,
// as in Blender: over the viewport (or over no window) all of them; over the outliner, which
// lists the scene's objects, Delete, F, Shift+D and the gizmo keys but not the fly keys; over any
// other panel (properties, statistics, menu bar) none, nor while a panel's widget is held.
struct SceneKeys {
  bool edit = false;
  bool fly = false;
};

bool within(const ImGuiWindow* window, const char* name) {
  for (; window; window = window->ParentWindow)
    if (std::strcmp(window->Name, name) == 0) return true;
  return false;
}

SceneKeys scene_keys() {
  const ImGuiContext& g = *ImGui::GetCurrentContext();
  if (g.ActiveId != 0 && !within(g.ActiveIdWindow, kViewportWindow)) return {};
  const ImGuiWindow* hovered = g.HoveredWindow;
  if (!hovered || within(hovered, kViewportWindow)) return {true, true};
  if (within(hovered, kOutlinerWindow)) return {true, false};
  return {};
}

void duplicate_selection(Document& doc) {
  const Selection sel = doc.selection;
  if (sel.kind == SelectionKind::none || sel.kind == SelectionKind::camera || sel.kind == SelectionKind::environment)
    return;
  const int copy = duplicate(doc.scene, sel);
  if (copy >= 0) doc.selection = {sel.kind, copy};
}

void fly_keys(Document& doc, EditorState& state);  // below handle_shortcuts, which it serves

}  // namespace

void handle_shortcuts(Document& doc, EditorState& state) {
  ImGuiIO& io = ImGui::GetIO();
  // Text fields own the keyboard (Escape there reverts the field).
  if (io.WantTextInput) return;
  // Escape closes an open menu, combo or context menu; a modal popup handles its own keys.
  const bool popup_open = ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId | ImGuiPopupFlags_AnyPopupLevel);
  if (popup_open && key_pressed(ImGuiKey_Escape) && !ImGui::GetTopMostPopupModal()) ImGui::ClosePopupsExceptModals();
  if (popup_open) return;  // the editor's shortcuts wait until it is closed
  handle_region_shortcuts(state);  // Ctrl+B, Ctrl+Alt+B (editor/ui_region.cpp)
  if (io.KeyCtrl) {
    if (key_pressed(ImGuiKey_Z)) {
      if (io.KeyShift) { if (doc.can_redo()) doc.redo(); }
      else if (doc.can_undo()) doc.undo();
    }
    if (key_pressed(ImGuiKey_Y) && doc.can_redo()) doc.redo();
    if (key_pressed(ImGuiKey_S)) save_document(doc, state, io.KeyShift);
    if (key_pressed(ImGuiKey_O)) request_action(doc, state, DocAction::open_dialog);
    if (key_pressed(ImGuiKey_N)) request_action(doc, state, DocAction::new_document);
    if (key_pressed(ImGuiKey_Q)) request_action(doc, state, DocAction::quit);
    return;
  }
  const SceneKeys reach = scene_keys();
  if (!reach.edit) return;
  if (key_pressed(ImGuiKey_Delete)) delete_item(doc, state, doc.selection);
  if (key_pressed(ImGuiKey_F)) frame_selection(doc);
  if (io.KeyShift && key_pressed(ImGuiKey_D)) duplicate_selection(doc);  // Blender's Shift+D
  // The gizmo's mode: G and R as in Blender; its S (scale) flies back here, so T. Not while a
  // gizmo drag is under way (it is measured in the mode it started in).
  if (state.tools.gizmo_handle < 0) {
    if (key_pressed(ImGuiKey_G)) state.tools.gizmo_mode = GizmoMode::move;
    if (key_pressed(ImGuiKey_R)) state.tools.gizmo_mode = GizmoMode::rotate;
    if (key_pressed(ImGuiKey_T)) state.tools.gizmo_mode = GizmoMode::scale;
  }
  if (reach.fly && !io.KeyShift) fly_keys(doc, state);  // Shift+D duplicates; it does not fly right
}

namespace {

// WASD fly as in the original program (Q/E down/up), speed relative to the target distance.
void fly_keys(Document& doc, EditorState& state) {
  glm::vec3 move{0};
  if (ImGui::IsKeyDown(ImGuiKey_W)) move.z += 1;
  if (ImGui::IsKeyDown(ImGuiKey_S)) move.z -= 1;
  if (ImGui::IsKeyDown(ImGuiKey_D)) move.x += 1;
  if (ImGui::IsKeyDown(ImGuiKey_A)) move.x -= 1;
  if (ImGui::IsKeyDown(ImGuiKey_E)) move.y += 1;
  if (ImGui::IsKeyDown(ImGuiKey_Q)) move.y -= 1;
  if (move != glm::vec3(0)) {
    Camera& cam = doc.scene.camera;
    float speed = std::max(0.5f, glm::length(cam.target - cam.position)) * 0.8f;
    fly(cam, move * speed * std::min(ImGui::GetIO().DeltaTime, 0.1f));
    state.tools.interacting = true;  // holding a key is one undo step, like a drag
    state.tools.navigated = true;
  }
}

}  // namespace

void draw_main_menu(Document& doc, EditorState& state) {
  draw_help_windows(state);
  if (!ImGui::BeginMainMenuBar()) return;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("New", "Ctrl+N")) request_action(doc, state, DocAction::new_document);
    if (ImGui::MenuItem("Open...", "Ctrl+O")) request_action(doc, state, DocAction::open_dialog);
    if (ImGui::BeginMenu("Open Recent", !state.flow.recent_files.empty())) {
      for (const auto& f : state.flow.recent_files)
        if (ImGui::MenuItem(f.string().c_str())) request_action(doc, state, DocAction::open_path, f);
      ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Examples", !state.flow.projects_dir.empty())) {
      // Each opens as an untitled copy: Save asks where to keep it (the examples stay as shipped).
      for (const std::filesystem::path& file : example_projects(state.flow.projects_dir))
        if (ImGui::MenuItem(file.stem().string().c_str()))
          request_action(doc, state, DocAction::open_example, file);
      ImGui::EndMenu();
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Save", "Ctrl+S")) save_document(doc, state, false);
    if (ImGui::MenuItem("Save As...", "Ctrl+Shift+S")) save_document(doc, state, true);
    ImGui::Separator();
    if (ImGui::MenuItem("Import scene...")) request_action(doc, state, DocAction::import_dialog);
    if (ImGui::MenuItem("Export scene...")) choose_file(doc, state, FilePurpose::export_scene);
    if (ImGui::MenuItem("Export Render...")) state.export_ui.show = true;
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) request_action(doc, state, DocAction::quit);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    if (ImGui::MenuItem("Undo", "Ctrl+Z", false, doc.can_undo())) doc.undo();
    if (ImGui::MenuItem("Redo", "Ctrl+Shift+Z", false, doc.can_redo())) doc.redo();
    ImGui::Separator();
    bool object = doc.selection.kind != SelectionKind::none && doc.selection.kind != SelectionKind::camera &&
                  doc.selection.kind != SelectionKind::environment;
    if (ImGui::MenuItem("Duplicate", "Shift+D", false, object)) duplicate_selection(doc);
    if (ImGui::MenuItem("Delete", "Del", false, object)) delete_item(doc, state, doc.selection);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Add")) {
    if (ImGui::MenuItem("Sphere")) doc.selection = {SelectionKind::sphere, add_sphere(doc.scene)};
    if (ImGui::MenuItem("Quad")) doc.selection = {SelectionKind::quad, add_quad(doc.scene)};
    ImGui::Separator();
    for (const MaterialTypeInfo& t : kMaterialTypes)
      if (ImGui::MenuItem((std::string("Material: ") + t.name).c_str()))
        doc.selection = {SelectionKind::material, add_material(doc.scene, t.type)};
    if (ImGui::MenuItem("Texture from file...")) choose_file(doc, state, FilePurpose::add_texture);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    if (ImGui::MenuItem("Frame selection", "F")) frame_selection(doc);
    ImGui::Separator();
    const bool dragging = state.tools.gizmo_handle >= 0;
    if (ImGui::MenuItem("Move gizmo", "G", state.tools.gizmo_mode == GizmoMode::move, !dragging))
      state.tools.gizmo_mode = GizmoMode::move;
    if (ImGui::MenuItem("Rotate gizmo", "R", state.tools.gizmo_mode == GizmoMode::rotate, !dragging))
      state.tools.gizmo_mode = GizmoMode::rotate;
    if (ImGui::MenuItem("Scale gizmo", "T", state.tools.gizmo_mode == GizmoMode::scale, !dragging))
      state.tools.gizmo_mode = GizmoMode::scale;
    ImGui::Separator();
    ImGui::MenuItem("Focus tool (click sets focus)", nullptr, &state.tools.focus_tool);
    if (ImGui::MenuItem("Invert vertical orbit", nullptr, &state.settings.invert_vertical_orbit)) settings_changed(state);
    if (ImGui::MenuItem("Camera")) doc.selection = {SelectionKind::camera, -1};
    if (ImGui::MenuItem("Environment")) doc.selection = {SelectionKind::environment, -1};
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Window")) {
    if (ImGui::MenuItem("Reset layout")) reset_layout();
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Help")) {
    ImGui::MenuItem("Controls", nullptr, &state.show_controls);
    ImGui::MenuItem("About Glint", nullptr, &state.show_about);
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
}

}  // namespace glint
