// The open document: the scene being edited, its file, the selection, and undo/redo.
//
// Undo is derived, like the renderer's change detection: at the end of every UI frame the
// editor calls end_frame(); if the scene differs from the last committed state and no drag is
// in progress, the previous state becomes an undo step. No widget has to register its edits,
// and a whole drag (mouse held on a slider or the gizmo) is one step. A run of navigation
// (orbits, pans, zooms, flights with nothing else changed) merges into one step, so that
// navigating never buries the scene edits before it; a deliberate camera setting (a typed field
// of view, a click-to-focus) is a step of its own.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "renderer/scene.h"

namespace glint {

enum class SelectionKind { none, sphere, quad, material, texture, environment, camera };

struct Selection {
  SelectionKind kind = SelectionKind::none;
  int index = -1;
  bool operator==(const Selection&) const = default;
};

class Document {
 public:
  Document();  // an untitled document holding new_scene()
  explicit Document(Scene scene, std::filesystem::path path = {});

  Scene scene;
  Selection selection;

  const std::filesystem::path& path() const { return path_; }  // empty when untitled
  std::string display_name() const;                             // file name or "Untitled"
  std::string window_title() const;  // "name.glint* - Glint" (the * marks unsaved changes)
  bool dirty() const;                // the scene differs from what was last saved or opened

  // Saves to `file` (Save As when it differs from path()), with asset paths relative to its
  // folder (save_project); afterwards the document is clean, holds those paths, and path() is
  // `file`. Throws ProjectError.
  void save(const std::filesystem::path& file);

  // Call once per UI frame, after the widgets ran. `interacting`: a drag is in progress.
  // `navigated`: the camera moved by navigation this frame (the edit pending since the last
  // step then merges with a navigation step before it, when it only moved the camera).
  void end_frame(bool interacting, bool navigated = false);
  bool can_undo() const { return !undo_.empty(); }
  bool can_redo() const { return !redo_.empty(); }
  void undo();
  void redo();
  // Commits any pending edit and makes the next edit a step of its own, even a camera change
  // right after camera moves (a recalled camera view is one undo step).
  void separate_next_step();

 private:
  struct State {
    Scene scene;
    Selection selection;
  };
  std::filesystem::path path_;
  Scene saved_;        // the scene as last saved or opened
  State committed_;    // the state the undo history ends at
  std::vector<State> undo_, redo_;
  bool pending_navigation_ = false;  // the edit not yet a step came from navigation
  bool last_step_navigation_ = false;  // the newest undo step was navigation only
};

// The scene of File > New: a floor, one sphere, a grey environment, default camera.
Scene new_scene();

}  // namespace glint
