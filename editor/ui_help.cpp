// The Help menu's windows (the controls sheet, About), the remembered settings, and files
// dropped on the window.
#include <algorithm>
#include <cctype>

#include "editor/scene_edits.h"
#include "editor/ui.h"
#include "editor/ui_context.h"
#include "renderer/build_info.h"
#include "renderer/texture_slots.h"

namespace glint {
namespace {

// The one list of the editor's controls (README's table says the same): every mouse gesture,
// key and menu path that does something beyond a plain menu item.
constexpr ControlLine kControls[] = {
    {"Left drag on empty space, right drag", "orbit around the target (as Blender; View > Invert vertical orbit)"},
    {"Middle drag, Shift + any drag", "pan"},
    {"Mouse wheel", "zoom (dolly towards the target)"},
    {"W A S D, Q E (pointer on the viewport)", "fly forward/left/back/right, down/up"},
    {"Click", "select (empty space: select nothing)"},
    {"Ctrl+click, or View > Focus tool", "set the focus distance on that surface"},
    {"G, R, T", "gizmo mode: move, rotate, scale (also the viewport's buttons)"},
    {"Drag a gizmo arrow (move)", "move the selection along a world axis"},
    {"Drag a gizmo ring (rotate)", "turn a quad about that world axis through its centre"},
    {"Drag a square / the circle (scale)", "scale a quad along that edge / uniformly; a sphere's radius"},
    {"Ctrl+B, then drag", "render region: only the rectangle takes samples (Ctrl+Alt+B: all again)"},
    {"F", "frame the selection"},
    {"Shift+D", "duplicate the selection, beside it"},
    {"Del", "delete the selection (a material in use asks)"},
    {"Click a number field", "type a value (Enter sets it, Escape reverts); drag it to change it"},
    {"Escape", "close an open menu or list"},
    {"Double-click / right-click in the outliner", "rename / rename, duplicate, delete"},
    {"Ctrl+Z, Ctrl+Shift+Z / Ctrl+Y", "undo, redo (a run of orbits, pans, zooms, flights is one step)"},
    {"Ctrl+N, Ctrl+O", "new, open"},
    {"Ctrl+S, Ctrl+Shift+S", "save, save as"},
    {"Ctrl+Q", "quit (asks about unsaved changes)"},
    {"File > Examples", "open an example project as an untitled copy"},
    {"Drop a file on the window", ".glint opens; .hdr/.exr: environment; image: colour texture"},
    {"Drag a panel's tab / edge", "dock it elsewhere or float it / resize it"},
};

std::string lower_extension(const std::filesystem::path& file) {
  std::string e = file.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

}  // namespace

std::span<const ControlLine> editor_controls() { return kControls; }

void settings_changed(EditorState& state) {
  if (state.on_settings_changed) state.on_settings_changed(state.settings);
}

void draw_help_windows(EditorState& state) {
  if (state.show_controls) {
    // As wide and tall as its table: every row shows whole.
    if (ImGui::Begin("Controls", &state.show_controls,
                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_AlwaysAutoResize)) {
      if (ImGui::BeginTable("controls", 2,
                            ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_SizingFixedFit)) {
        ImGui::TableSetupColumn("Input");
        ImGui::TableSetupColumn("Action");
        ImGui::TableHeadersRow();
        for (const ControlLine& c : kControls) {
          ImGui::TableNextRow();
          ImGui::TableNextColumn();
          ImGui::TextUnformatted(c.input);
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
      ImGui::TextUnformatted(glint_software().c_str());
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
