// The open document and its derived undo history (see document.h).
#include "editor/document.h"

#include <system_error>

#include "renderer/project_file.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

// Undo steps kept; the oldest are dropped first. Scenes are small values, so 200 copies are
// cheap, and nobody undoes further than that.
constexpr size_t kMaxUndoSteps = 200;

// A selection that points past the end of its list (after an undo removed the object) is
// replaced by none, so the UI never indexes out of range.
Selection valid_selection(const Scene& scene, Selection s) {
  auto in = [&](size_t n) { return s.index >= 0 && static_cast<size_t>(s.index) < n; };
  switch (s.kind) {
    case SelectionKind::sphere: return in(scene.spheres.size()) ? s : Selection{};
    case SelectionKind::quad: return in(scene.quads.size()) ? s : Selection{};
    case SelectionKind::material: return in(scene.materials.size()) ? s : Selection{};
    case SelectionKind::texture: return in(scene.textures.size()) ? s : Selection{};
    default: return s;
  }
}

// True when the scenes differ at most in the camera.
bool same_but_camera(const Scene& a, const Scene& b) {
  Scene t = a;
  t.camera = b.camera;
  return t == b;
}

fs::path current_folder() {
  std::error_code ec;
  fs::path p = fs::current_path(ec);
  return ec ? fs::path() : p;
}

}  // namespace

Scene new_scene() {
  Scene s;
  s.base_dir = current_folder();  // an unsaved scene resolves paths against the current folder
  s.environment.color = {0.5f, 0.5f, 0.5f};
  s.environment.intensity = 1;

  Material grey;
  grey.name = "grey_matte";
  grey.type = MaterialType::matte;
  grey.color = {0.5f, 0.5f, 0.5f};
  Material white;
  white.name = "white_glossy";
  white.type = MaterialType::glossy;
  white.color = {0.9f, 0.9f, 0.9f};
  white.roughness = 0.2f;
  s.materials = {grey, white};

  Quad floor;
  floor.name = "floor";
  floor.material = grey.name;
  // Normal cross(p1 - p0, p2 - p0) points up (+Y).
  floor.corners = {glm::vec3{-5, 0, -5}, glm::vec3{-5, 0, 5}, glm::vec3{5, 0, -5},
                   glm::vec3{5, 0, 5}};
  floor.uvs = {glm::vec2{0, 0}, glm::vec2{0, 5}, glm::vec2{5, 0}, glm::vec2{5, 5}};
  s.quads = {floor};

  Sphere ball;
  ball.name = "sphere";
  ball.center = {0, 0.5f, 0};
  ball.radius = 0.5f;
  ball.material = white.name;
  s.spheres = {ball};

  s.camera.position = {0, 1, 5};
  s.camera.target = ball.center;
  s.camera.up = {0, 1, 0};
  s.camera.vfov_deg = 40;
  s.camera.aperture_radius = 0;
  s.camera.focus_distance = glm::length(s.camera.target - s.camera.position);
  return s;
}

Document::Document() : Document(new_scene()) {}

Document::Document(Scene scene_in, std::filesystem::path path)
    : scene(std::move(scene_in)), path_(std::move(path)), saved_(scene), committed_{scene, {}} {}

std::string Document::display_name() const {
  return path_.empty() ? std::string("Untitled") : path_.filename().string();
}

std::string Document::window_title() const {
  return display_name() + (dirty() ? "*" : "") + " - Glint";
}

bool Document::dirty() const { return scene != saved_; }

void Document::save(const std::filesystem::path& file) {
  end_frame(false);  // an edit of this very frame belongs to the history before the save
  save_project(scene, file);  // throws ProjectError; nothing below runs on failure
  const fs::path folder = fs::absolute(file).parent_path();  // what load_project will report
  // The scene as the file now holds it (asset paths relative to the new folder).
  auto as_saved = [&](const Scene& s) { return relative_asset_paths(rebase_asset_paths(s, folder), folder); };
  scene = as_saved(scene);
  // The history moves along, so that undo after Save As reverts only the user's edits and
  // keeps the asset paths resolvable from the new folder.
  for (State& s : undo_) s.scene = as_saved(s.scene);
  for (State& s : redo_) s.scene = as_saved(s.scene);
  committed_ = {scene, selection};
  saved_ = scene;
  path_ = file;
  pending_navigation_ = last_step_navigation_ = false;
}

void Document::end_frame(bool interacting, bool navigated) {
  pending_navigation_ = pending_navigation_ || navigated;
  if (scene == committed_.scene) {
    pending_navigation_ = false;  // navigated back to where it was: nothing to record
    // Remember the selection of the last quiet frame: an undo step restores the selection the
    // edit was made with (e.g. undoing a delete selects nothing stale).
    committed_.selection = selection;
    return;
  }
  if (interacting) return;  // a drag in progress becomes one step when it ends
  const bool navigation = pending_navigation_ && same_but_camera(scene, committed_.scene);
  pending_navigation_ = false;
  if (navigation && last_step_navigation_ && !undo_.empty()) {
    // Continues a run of navigation: the step before the run stays the one to undo to.
    redo_.clear();
    committed_ = {scene, selection};
    return;
  }
  last_step_navigation_ = navigation;
  undo_.push_back(std::move(committed_));
  if (undo_.size() > kMaxUndoSteps) undo_.erase(undo_.begin());
  redo_.clear();
  committed_ = {scene, selection};
}

void Document::separate_next_step() {
  end_frame(false);
  pending_navigation_ = last_step_navigation_ = false;
}

void Document::undo() {
  end_frame(false);  // commit a pending edit first so that undo never loses it silently
  if (undo_.empty()) return;
  pending_navigation_ = last_step_navigation_ = false;
  redo_.push_back({scene, selection});
  committed_ = std::move(undo_.back());
  undo_.pop_back();
  scene = committed_.scene;
  selection = valid_selection(scene, committed_.selection);
  committed_.selection = selection;
}

void Document::redo() {
  end_frame(false);  // a new pending edit would clear redo_; then there is nothing to redo
  if (redo_.empty()) return;
  pending_navigation_ = last_step_navigation_ = false;
  undo_.push_back({scene, selection});
  if (undo_.size() > kMaxUndoSteps) undo_.erase(undo_.begin());
  committed_ = std::move(redo_.back());
  redo_.pop_back();
  scene = committed_.scene;
  selection = valid_selection(scene, committed_.selection);
  committed_.selection = selection;
}

}  // namespace glint
