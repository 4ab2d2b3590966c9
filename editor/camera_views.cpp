#include "editor/camera_views.h"

#include "renderer/scene_validation.h"

namespace glint {
namespace {

bool valid_index(const Scene& scene, int index) {
  return index >= 0 && static_cast<size_t>(index) < scene.views.size();
}

bool name_taken(const Scene& scene, const std::string& name, int except = -1) {
  for (size_t i = 0; i < scene.views.size(); ++i)
    if (static_cast<int>(i) != except && scene.views[i].name == name) return true;
  return false;
}

}  // namespace

std::string unique_view_name(const Scene& scene, const std::string& base) {
  const std::string stem = base.empty() ? "View" : base;
  if (!name_taken(scene, stem)) return stem;
  for (size_t n = 2;; ++n) {
    std::string candidate = stem + " " + std::to_string(n);
    if (!name_taken(scene, candidate)) return candidate;
  }
}

int save_view(Scene& scene, const std::string& name) {
  if (scene.views.size() >= kMaxCameraViews) return -1;
  scene.views.push_back({unique_view_name(scene, name), scene.camera});
  return static_cast<int>(scene.views.size()) - 1;
}

bool recall_view(Scene& scene, int index) {
  if (!valid_index(scene, index)) return false;
  scene.camera = scene.views[index].camera;
  return true;
}

bool recall_view(Document& doc, int index) {
  if (!valid_index(doc.scene, index)) return false;
  doc.separate_next_step();
  return recall_view(doc.scene, index);
}

bool rename_view(Scene& scene, int index, const std::string& name) {
  if (!valid_index(scene, index) || name.empty() || name_taken(scene, name, index)) return false;
  scene.views[index].name = name;
  return true;
}

bool delete_view(Scene& scene, int index) {
  if (!valid_index(scene, index)) return false;
  scene.views.erase(scene.views.begin() + index);
  return true;
}

bool update_view(Scene& scene, int index) {
  if (!valid_index(scene, index)) return false;
  scene.views[index].camera = scene.camera;
  return true;
}

}  // namespace glint
