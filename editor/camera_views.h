// Camera views: named bookmarks of the camera, saved in the project (Scene::views). Plain edits
// of a scene, no UI; the views are in no digest, so none of these resets the render but the
// recall, which moves the camera.
#pragma once

#include <string>

#include "editor/document.h"
#include "renderer/scene.h"

namespace glint {

// A view name not used yet: base, base 2, base 3, ...
std::string unique_view_name(const Scene& scene, const std::string& base);
// Saves the current camera as a new view named `name` (made unique; "View" when empty).
// Returns its index.
int save_view(Scene& scene, const std::string& name = {});
// Puts view `index` into the camera; false (and nothing changes) when there is no such view.
bool recall_view(Scene& scene, int index);
// The recall as its own undo step (never merged into the camera moves before it).
bool recall_view(Document& doc, int index);
// Renames; false (and nothing changes) when the name is empty or another view has it.
bool rename_view(Scene& scene, int index, const std::string& name);
bool delete_view(Scene& scene, int index);
// Overwrites view `index` with the current camera (keeping its name).
bool update_view(Scene& scene, int index);

}  // namespace glint
