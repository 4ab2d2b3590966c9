// Document actions: new, open, save, save as, the unsaved-changes guard, choosing files (native
// dialog or typed path), and the modals that go with them.
#include <algorithm>
#include <cstring>

#include "editor/file_dialogs.h"
#include "editor/scene_edits.h"
#include "editor/ui.h"
#include "editor/ui_context.h"
#include "renderer/image.h"
#include "renderer/project_file.h"
#include "renderer/scene_images.h"
#include "renderer/texture_slots.h"

namespace glint {
namespace fs = std::filesystem;
namespace {

// Throws the first problem of the scene's images as loading the project would report it: an
// unreadable or undecodable file, a bad texel, more texture memory than kMaxImageBytes.
void refuse_image_problems(const Scene& scene) {
  const std::vector<ProjectError> problems = check_scene_images(scene);
  if (!problems.empty()) throw std::runtime_error(problems.front().what());
}

const char* const kUnsavedPopup = "Unsaved changes";
const char* const kPathPopup = "Choose a file";
const char* const kErrorPopup = "Error";

// A path as the project stores it: relative when below the project's folder.
std::string project_relative(const Scene& scene, const fs::path& file) {
  std::error_code ec;
  fs::path base = fs::absolute(scene.base_dir.empty() ? fs::current_path(ec) : scene.base_dir, ec).lexically_normal();
  fs::path abs = fs::absolute(file, ec).lexically_normal();
  fs::path rel = abs.lexically_relative(base);
  if (!rel.empty() && *rel.begin() != "..") return rel.generic_string();
  return abs.string();
}

// "Saved FILE", and the images whose paths stayed absolute (no relative form from the project's
// folder: another drive, on Windows), which break when the project moves.
std::string saved_message(const Document& doc) {
  std::string message = "Saved " + doc.path().string();
  std::vector<std::string> absolute;
  for (const Texture& t : doc.scene.textures)
    if (fs::path(t.path).is_absolute()) absolute.push_back(t.path);
  if (fs::path(doc.scene.environment.texture).is_absolute()) absolute.push_back(doc.scene.environment.texture);
  if (!absolute.empty())
    message += " (" + absolute.front() + (absolute.size() > 1 ? " and others" : "") +
               " kept absolute: no relative path leads there from the project's folder)";
  return message;
}

void perform(Document& doc, EditorState& state, DocAction action, const fs::path& path) {
  switch (action) {
    case DocAction::new_document: new_document(doc, state); break;
    case DocAction::open_dialog: choose_file(doc, state, FilePurpose::open_project); break;
    case DocAction::open_path: open_document(doc, state, path); break;
    case DocAction::open_example: open_example_copy(doc, state, path); break;
    case DocAction::import_dialog: choose_file(doc, state, FilePurpose::import_scene); break;
    case DocAction::quit: state.flow.quit_approved = true; break;
    case DocAction::none: break;
  }
}

struct DialogSpec {
  const char* title;
  bool save;
  std::vector<std::string> filters;
  const char* description;
};

DialogSpec dialog_spec(FilePurpose purpose) {
  switch (purpose) {
    case FilePurpose::open_project: return {"Open project", false, {"*.glint"}, "Glint projects"};
    case FilePurpose::save_project_as: return {"Save project as", true, {"*.glint"}, "Glint projects"};
    case FilePurpose::texture_slot:
    case FilePurpose::add_texture:
      return {"Choose a texture image", false, {"*.png", "*.jpg", "*.jpeg", "*.hdr", "*.exr"}, "Images"};
    case FilePurpose::environment: return {"Choose an environment map", false, {"*.hdr", "*.exr"}, "HDR images"};
    case FilePurpose::export_output: return {"Export render to", true, {"*.png", "*.hdr", "*.exr"}, "Images"};
    case FilePurpose::import_scene: return {"Import a Mitsuba 3 or pbrt-v4 scene", false, {"*.xml", "*.pbrt"}, "Mitsuba 3 and pbrt-v4 scenes"};
    case FilePurpose::export_scene: return {"Export scene to", true, {"*.xml", "*.pbrt"}, "Mitsuba 3 (.xml) and pbrt-v4 (.pbrt) scenes"};
  }
  return {"Choose a file", false, {}, ""};
}

}  // namespace

void show_error(EditorState& state, const std::string& message) {
  state.messages.error = message;
  state.messages.open_error = true;
}

void show_message(EditorState& state, const std::string& message) {
  state.messages.message = message;
  state.messages.message_until = ImGui::GetTime() + 4.0;
}

void show_note(EditorState& state, const std::string& note) {
  const double now = ImGui::GetTime();
  if (!state.messages.note.empty() && now < state.messages.note_until) state.messages.note += "; " + note;
  else state.messages.note = note;
  state.messages.note_until = now + 10.0;
}

void request_action(Document& doc, EditorState& state, DocAction action, fs::path path) {
  if (doc.dirty()) {
    state.flow.pending = action;
    state.flow.pending_path = std::move(path);
    state.flow.open_unsaved_prompt = true;
    return;
  }
  perform(doc, state, action, path);
}

void new_document(Document& doc, EditorState& state) {
  doc = Document();
  state.thumbnails.clear();
  show_message(state, "New project");
}

bool open_document(Document& doc, EditorState& state, const fs::path& file) {
  try {
    Scene scene = load_project(file);
    doc = Document(std::move(scene), fs::absolute(file));
    state.thumbnails.clear();
    if (state.flow.on_opened_or_saved) state.flow.on_opened_or_saved(doc.path());
    show_message(state, "Opened " + file.string());
    return true;
  } catch (const std::exception& e) {
    show_error(state, e.what());
    return false;
  }
}

bool save_document(Document& doc, EditorState& state, bool save_as) {
  if (save_as || doc.path().empty()) {
    choose_file(doc, state, FilePurpose::save_project_as);
    return false;  // completes when a file is chosen (perhaps in a later frame)
  }
  try {
    doc.save(doc.path());
    if (state.flow.on_opened_or_saved) state.flow.on_opened_or_saved(doc.path());
    show_message(state, saved_message(doc));
    return true;
  } catch (const std::exception& e) {
    show_error(state, e.what());
    return false;
  }
}

std::string file_dialog_start(const Document& doc, const EditorState& state, FilePurpose purpose) {
  std::error_code ec;
  const fs::path folder = doc.path().empty() ? fs::current_path(ec) : fs::absolute(doc.path(), ec).parent_path();
  switch (purpose) {
    case FilePurpose::save_project_as:
      return doc.path().empty() ? (folder / "untitled.glint").string() : doc.path().string();
    case FilePurpose::export_output: return state.export_ui.settings.output.string();
    case FilePurpose::texture_slot:
    case FilePurpose::add_texture:
    case FilePurpose::environment:
      // A folder, never the project file: images usually sit in its assets folder.
      if (fs::is_directory(folder / "assets", ec)) return (folder / "assets").string() + "/";
      return folder.string() + "/";
    case FilePurpose::open_project:
    case FilePurpose::import_scene: return folder.string() + "/";
    case FilePurpose::export_scene:
      return (folder / ((doc.path().empty() ? std::string("untitled") : doc.path().stem().string()) + ".xml")).string();
  }
  return folder.string() + "/";
}

void choose_file(Document& doc, EditorState& state, FilePurpose purpose) {
  DialogSpec spec = dialog_spec(purpose);
  const std::string start = file_dialog_start(doc, state, purpose);
  if (state.flow.native_dialogs) {
    if (state.flow.dialog.running()) return;  // one at a time
    state.flow.dialog_purpose = purpose;
    state.flow.dialog.start({spec.save, spec.title, start, spec.description, spec.filters}, state.flow.dialog_runner);
    return;
  }
  state.flow.prompt.request_open = true;
  state.flow.prompt.purpose = purpose;
  state.flow.prompt.title = spec.title;
  std::snprintf(state.flow.prompt.buffer, sizeof state.flow.prompt.buffer, "%s", start.c_str());
}

void apply_chosen_file(Document& doc, EditorState& state, FilePurpose purpose, const std::string& file) {
  fs::path path(file);
  try {
    switch (purpose) {
      case FilePurpose::open_project: open_document(doc, state, path); break;
      case FilePurpose::save_project_as: {
        if (path.extension().empty()) path += ".glint";
        doc.save(path);
        if (state.flow.on_opened_or_saved) state.flow.on_opened_or_saved(doc.path());
        show_message(state, saved_message(doc));
        // A save that was asked for by the unsaved-changes prompt continues its action.
        DocAction next = state.flow.pending;
        state.flow.pending = DocAction::none;
        perform(doc, state, next, state.flow.pending_path);
        break;
      }
      case FilePurpose::add_texture:
      case FilePurpose::texture_slot: {
        {  // refuse what the project could not load before it reaches the scene
          Scene candidate = doc.scene;
          add_texture(candidate, path);
          refuse_image_problems(candidate);
        }
        int t = add_texture(doc.scene, path);
        if (purpose == FilePurpose::texture_slot && state.flow.slot_material >= 0 &&
            state.flow.slot_material < static_cast<int>(doc.scene.materials.size()) &&
            state.flow.slot_index >= 0 && state.flow.slot_index < static_cast<int>(kTextureSlots.size())) {
          Material& m = doc.scene.materials[state.flow.slot_material];
          m.*kTextureSlots[state.flow.slot_index].member = doc.scene.textures[t].name;
        }
        break;
      }
      case FilePurpose::environment: {
        ImageInfo info = probe_image(path);
        if (!info.high_dynamic_range && path.extension() != ".hdr" && path.extension() != ".exr")
          throw std::runtime_error(file + ": the environment must be an .hdr or .exr image");
        Scene candidate = doc.scene;
        candidate.environment.texture = project_relative(doc.scene, path);
        refuse_image_problems(candidate);
        doc.scene.environment.texture = candidate.environment.texture;
        break;
      }
      case FilePurpose::export_output: state.export_ui.settings.output = path; break;
      case FilePurpose::import_scene: import_document(doc, state, path); break;
      case FilePurpose::export_scene: export_document(doc, state, path); break;
    }
  } catch (const std::exception& e) {
    if (purpose == FilePurpose::save_project_as) state.flow.pending = DocAction::none;
    show_error(state, e.what());
  }
}

void draw_document_modals(Document& doc, EditorState& state) {
  poll_file_dialog(doc, state);
  if (state.flow.open_unsaved_prompt) {
    ImGui::OpenPopup(kUnsavedPopup);
    state.flow.open_unsaved_prompt = false;
  }
  if (ImGui::BeginPopupModal(kUnsavedPopup, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("%s has unsaved changes.", doc.display_name().c_str());
    ImGui::TextUnformatted("Save them first?");
    ImGui::Spacing();
    if (ImGui::Button("Save", ImVec2(ui_units(90), 0))) {
      ImGui::CloseCurrentPopup();
      if (doc.path().empty()) {
        choose_file(doc, state, FilePurpose::save_project_as);  // continues the action when saved
      } else if (save_document(doc, state, false)) {
        DocAction next = state.flow.pending;
        state.flow.pending = DocAction::none;
        perform(doc, state, next, state.flow.pending_path);
      } else {
        state.flow.pending = DocAction::none;
      }
    }
    ImGui::SameLine();
    if (ImGui::Button("Discard", ImVec2(ui_units(90), 0))) {
      ImGui::CloseCurrentPopup();
      DocAction next = state.flow.pending;
      state.flow.pending = DocAction::none;
      perform(doc, state, next, state.flow.pending_path);
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel", ImVec2(ui_units(90), 0)) || ImGui::IsKeyPressed(ImGuiKey_Escape)) {
      ImGui::CloseCurrentPopup();
      state.flow.pending = DocAction::none;
    }
    ImGui::EndPopup();
  }

  if (state.flow.prompt.request_open) {
    ImGui::OpenPopup(kPathPopup);
    state.flow.prompt.request_open = false;
  }
  ImGui::SetNextWindowSize(ImVec2(ui_units(560), 0), ImGuiCond_Appearing);
  if (ImGui::BeginPopupModal(kPathPopup, nullptr, ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::TextUnformatted(state.flow.prompt.title.c_str());
    ImGui::TextDisabled("No file dialog is available here: type the path.");
    if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
    ImGui::SetNextItemWidth(-1);
    bool enter = ImGui::InputText("##path", state.flow.prompt.buffer, sizeof state.flow.prompt.buffer,
                                  ImGuiInputTextFlags_EnterReturnsTrue);
    if (ImGui::Button("OK", ImVec2(ui_units(90), 0)) || enter) {
      ImGui::CloseCurrentPopup();
      std::string chosen = state.flow.prompt.buffer;
      if (!chosen.empty()) apply_chosen_file(doc, state, state.flow.prompt.purpose, chosen);
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel", ImVec2(ui_units(90), 0)) || ImGui::IsKeyPressed(ImGuiKey_Escape)) {
      ImGui::CloseCurrentPopup();
      if (state.flow.prompt.purpose == FilePurpose::save_project_as) state.flow.pending = DocAction::none;
    }
    ImGui::EndPopup();
  }

  if (state.messages.open_error) {
    ImGui::OpenPopup(kErrorPopup);
    state.messages.open_error = false;
    state.messages.error_enter_released = false;
  }
  ImGui::SetNextWindowSize(ImVec2(ui_units(520), 0), ImGuiCond_Appearing);
  if (ImGui::BeginPopupModal(kErrorPopup, nullptr, ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::PushTextWrapPos(0);
    ImGui::TextUnformatted(state.messages.error.c_str());
    ImGui::PopTextWrapPos();
    // The Enter that confirmed a typed path opens this box in the same frame (and may repeat
    // while held): only a press that follows a release closes it.
    const ImGuiKey enter = ImGuiKey_Enter;
    const bool enter_closes = state.messages.error_enter_released && ImGui::IsKeyPressed(enter, false);
    if (!ImGui::IsKeyDown(enter)) state.messages.error_enter_released = true;
    if (ImGui::Button("OK", ImVec2(ui_units(90), 0)) || enter_closes) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  draw_delete_prompt(doc, state);
}

std::vector<fs::path> example_projects(const fs::path& projects_dir) {
  std::vector<fs::path> found;
  if (projects_dir.empty()) return found;
  std::error_code ec;
  for (fs::directory_iterator it(projects_dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().extension() == ".glint" && it->is_regular_file(ec)) found.push_back(it->path());
  std::sort(found.begin(), found.end());
  return found;
}

bool open_example_copy(Document& doc, EditorState& state, const fs::path& file) {
  try {
    // load_project sets base_dir to the example's folder: its assets resolve from there, and
    // Save As rebases them to wherever the copy is saved.
    doc = Document(load_project(file));
    state.thumbnails.clear();
    show_message(state, "Opened example " + file.stem().string() + " as an untitled copy (Save asks where to keep it)");
    return true;
  } catch (const std::exception& e) {
    show_error(state, e.what());
    return false;
  }
}

fs::path find_projects_dir(const std::vector<fs::path>& starts) {
  std::error_code ec;
  for (fs::path dir : starts) {
    dir = fs::absolute(dir, ec);
    for (int up = 0; up < 8 && !dir.empty(); ++up) {
      if (fs::exists(dir / "projects" / "default.glint", ec)) return dir / "projects";
      if (dir == dir.parent_path()) break;
      dir = dir.parent_path();
    }
  }
  return {};
}

}  // namespace glint
