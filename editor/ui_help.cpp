// The Help menu's windows (the controls sheet, About), the remembered settings, and files
// dropped on the window.
#include <algorithm>
#include <cctype>

#include "editor/scene_edits.h"
#include "editor/ui.h"
#include "editor/ui_context.h"
#include "renderer/texture_slots.h"

namespace glint {
namespace {

struct Control {
  const char* keys;
  const char* action;
};

// The one list of the editor's controls (README's table says the same).
constexpr Control kControls[] = {
    {"Left drag (viewport)", "orbit around the target"},
    {"Middle drag, Shift+left drag", "pan"},
    {"Mouse wheel", "zoom (dolly towards the target)"},
    {"W A S D, Q E", "fly forward/left/back/right, down/up"},
    {"Click", "select (empty space: select nothing)"},
    {"Ctrl+click", "set the focus distance on that surface"},
    {"G, R, T", "gizmo mode: move, rotate, scale (also the viewport's buttons)"},
    {"Drag a gizmo arrow (move)", "move the selection along a world axis"},
    {"Drag a gizmo ring (rotate)", "turn a quad about that world axis through its centre"},
    {"Drag a square / the circle (scale)", "scale a quad along that edge / uniformly; a sphere's radius"},
    {"Ctrl+B, then drag", "render region: only the rectangle takes samples (Ctrl+Alt+B: all again)"},
    {"F", "frame the selection"},
    {"Del", "delete the selection (a material in use asks)"},
    {"1 2 3 4", "open an example project (asks about unsaved changes)"},
    {"Ctrl+Z, Ctrl+Shift+Z / Ctrl+Y", "undo, redo (a run of camera moves is one step)"},
    {"Ctrl+N, Ctrl+O", "new, open"},
    {"Ctrl+S, Ctrl+Shift+S", "save, save as"},
    {"Ctrl+Q", "quit (asks about unsaved changes)"},
    {"Drop a file on the window", ".glint opens; .hdr/.exr: environment; image: colour texture"},
};

std::string lower_extension(const std::filesystem::path& file) {
  std::string e = file.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

}  // namespace

void settings_changed(EditorState& state) {
  if (state.on_settings_changed) state.on_settings_changed(state.settings);
}

void draw_help_windows(EditorState& state) {
  if (state.show_controls) {
    ImGui::SetNextWindowSize(ImVec2(ui_units(560), 0), ImGuiCond_Appearing);
    if (ImGui::Begin("Controls", &state.show_controls, ImGuiWindowFlags_NoSavedSettings)) {
      if (ImGui::BeginTable("controls", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
        ImGui::TableSetupColumn("Input");
        ImGui::TableSetupColumn("Action");
        ImGui::TableHeadersRow();
        for (const Control& c : kControls) {
          ImGui::TableNextRow();
          ImGui::TableNextColumn();
          ImGui::TextUnformatted(c.keys);
          ImGui::TableNextColumn();
          ImGui::TextUnformatted(c.action);
        }
        ImGui::EndTable();
      }
      ImGui::TextDisabled("Hover any property for what it does.");
    }
    ImGui::End();
  }
  if (state.show_about) {
    if (ImGui::Begin("About Glint", &state.show_about,
                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_AlwaysAutoResize)) {
      ImGui::Text("Glint %s", GLINT_VERSION);
      ImGui::TextUnformatted("A scene editor with a progressive GPU path tracer.");
      ImGui::Text("Dear ImGui %s", IMGUI_VERSION);
      ImGui::TextDisabled("glint --help lists the command line.");
    }
    ImGui::End();
  }
}

std::string drop_file(Document& doc, EditorState& state, const std::filesystem::path& file) {
  const std::string ext = lower_extension(file);
  if (ext == ".glint") {
    request_action(doc, state, DocAction::open_path, file);
    return "Opening " + file.string();
  }
  const std::string before_error = state.messages.error;
  state.messages.error.clear();
  std::string done;
  if (ext == ".hdr" || ext == ".exr") {
    apply_chosen_file(doc, state, FilePurpose::environment, file.string());
    done = "Environment: " + file.filename().string();
  } else {
    // The material of the selected object, or the selected material.
    int material = -1;
    const Selection sel = doc.selection;
    if (sel.kind == SelectionKind::sphere && sel.index >= 0 && sel.index < int(doc.scene.spheres.size()))
      material = find_material(doc.scene, doc.scene.spheres[sel.index].material);
    else if (sel.kind == SelectionKind::quad && sel.index >= 0 && sel.index < int(doc.scene.quads.size()))
      material = find_material(doc.scene, doc.scene.quads[sel.index].material);
    else if (sel.kind == SelectionKind::material)
      material = sel.index;
    if (material < 0) {
      show_error(state, file.string() + ": select an object or a material first, then drop the image on it");
      return {};
    }
    state.flow.slot_material = material;
    state.flow.slot_index = static_cast<int>(texture_slot_index(&Material::color_texture));
    apply_chosen_file(doc, state, FilePurpose::texture_slot, file.string());
    done = "Colour texture of " + doc.scene.materials[material].name + ": " + file.filename().string();
  }
  if (!state.messages.error.empty()) return {};  // refused: the error box says why
  state.messages.error = before_error;
  show_message(state, done);
  return done;
}

}  // namespace glint
