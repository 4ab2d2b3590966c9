// State the editor keeps between runs, outside any project: recent files, the user's settings
// and crash recovery.
//
// Every function takes an optional `dir`: the folder that holds the files directly. Left empty,
// it is the default (config_dir() or state_dir()); tests pass a temporary folder instead.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "editor/document.h"
#include "editor/viewport_frame.h"
#include "renderer/scene.h"

namespace glint {

// $XDG_CONFIG_HOME/glint, else ~/.config/glint (recent.json lives here).
std::filesystem::path config_dir(const std::filesystem::path& dir = {});
// $XDG_STATE_HOME/glint, else ~/.local/state/glint (recovery.glint and recovery.json).
std::filesystem::path state_dir(const std::filesystem::path& dir = {});

// ---- Recent files: up to 10 absolute paths, most recent first, in recent.json.
constexpr size_t kMaxRecentFiles = 10;
std::filesystem::path recent_files_path(const std::filesystem::path& dir = {});
// A missing or unreadable file gives an empty list (never throws).
std::vector<std::filesystem::path> load_recent_files(const std::filesystem::path& dir = {});
// Moves `file` (made absolute) to the front, drops duplicates and the overflow, saves, and
// returns the new list. Saving is best effort (a read-only home must not stop the editor).
std::vector<std::filesystem::path> add_recent_file(const std::filesystem::path& file,
                                                   const std::filesystem::path& dir = {});
// Removes `file` (e.g. it failed to open), saves, returns the new list.
std::vector<std::filesystem::path> remove_recent_file(const std::filesystem::path& file,
                                                      const std::filesystem::path& dir = {});

// ---- Settings the user chose, remembered between runs (settings.json in config_dir()).
struct EditorSettings {
  ViewportResolution preview = ViewportResolution::automatic;
  std::filesystem::path export_dir;  // the export dialog's last folder; empty: not chosen yet
  bool operator==(const EditorSettings&) const = default;
};
std::filesystem::path settings_path(const std::filesystem::path& dir = {});
// Missing, unreadable or unknown values give the defaults (never throws).
EditorSettings load_editor_settings(const std::filesystem::path& dir = {});
// Best effort, atomic (a read-only home must not stop the editor).
void save_editor_settings(const EditorSettings& settings, const std::filesystem::path& dir = {});
// The export dialog's first folder when none was remembered: the user's Pictures folder
// (XDG_PICTURES_DIR, else ~/Pictures when it exists), else the home folder; never the project's
// folder, which is often a source repository.
std::filesystem::path default_export_dir();

// ---- Crash recovery. The editor writes the recovery file every few seconds while the document
// is dirty and deletes it on a clean exit, so one found at start means the last run crashed.
struct Recovery {
  std::filesystem::path file;      // the recovery project (recovery.glint)
  std::filesystem::path original;  // the document's file when it was written; empty: untitled
  Scene scene;                     // the recovered scene, base_dir and asset paths as they were
};
std::filesystem::path recovery_file_path(const std::filesystem::path& dir = {});
// Writes recovery.glint and the sidecar recovery.json (original path and base folder), each
// atomically. Throws ProjectError on IO failure.
void write_recovery(const Document& doc, const std::filesystem::path& dir = {});
// The recovery left by a crashed run, or nullopt (none, or unreadable).
std::optional<Recovery> find_recovery(const std::filesystem::path& dir = {});
void discard_recovery(const std::filesystem::path& dir = {});
// A document holding the recovered scene, dirty: its path is the original file (if any), and
// when the original still opens, undo goes back to it.
Document open_recovery(const Recovery& recovery);

// Calls write_recovery at most every `interval_s` while the document is dirty and changed since
// the last write, and discards the recovery it wrote once the document is clean (saved). Never
// touches a recovery it did not write (the one offered at start). Call update() every frame.
class Autosave {
 public:
  explicit Autosave(std::filesystem::path dir = {}, double interval_s = 10);
  // Returns true when it wrote the recovery file this call.
  bool update(const Document& doc, double now_s);
  // Clean exit: deletes the recovery file this session wrote (not one offered and unanswered).
  void finish();
  const std::string& last_error() const { return last_error_; }

 private:
  std::filesystem::path dir_;
  double interval_s_;
  double last_write_s_ = 0;
  bool attempted_ = false;
  bool wrote_ = false;
  std::optional<Scene> written_;
  std::string last_error_;
};

}  // namespace glint
