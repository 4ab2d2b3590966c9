// State the editor keeps between runs, outside any project: recent files, the user's settings
// and crash recovery.
//
// Every function takes an optional `dir`: the folder that holds the files directly. Left empty,
// it is the default (config_dir() or state_dir()); tests pass a temporary folder instead.
#pragma once

#include <ctime>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "editor/document.h"
#include "editor/recovery_lock.h"
#include "editor/viewport_frame.h"
#include "renderer/scene.h"

namespace glint {

// $XDG_CONFIG_HOME/glint, else ~/.config/glint (recent.json, settings.json, layout.ini).
std::filesystem::path config_dir(const std::filesystem::path& dir = {});
// $XDG_STATE_HOME/glint, else ~/.local/state/glint (the recovery files).
std::filesystem::path state_dir(const std::filesystem::path& dir = {});

// Problems with these files never stop the editor. They are read with read_state_file
// (renderer/state_file.h: a FIFO, a folder or a file over the cap is a problem, never a hang or
// a crash) and written with write_state_file_atomically (a link or other non-regular file at
// the path is refused, never written through). A load that fails falls back to the defaults,
// a save that fails leaves the file as it was; either sets `note` to one line naming the file,
// the problem and the consequence, and clears it when there was none.

// ---- Recent files: up to 10 absolute paths, most recent first, in recent.json.
constexpr size_t kMaxRecentFiles = 10;
std::filesystem::path recent_files_path(const std::filesystem::path& dir = {});
// A missing file gives an empty list, without a note.
std::vector<std::filesystem::path> load_recent_files(std::string& note, const std::filesystem::path& dir = {});
// Moves `file` (made absolute) to the front, drops duplicates and the overflow, saves, and
// returns the new list. A list that could not be read (as opposed to one that is not valid
// JSON) is not overwritten.
std::vector<std::filesystem::path> add_recent_file(const std::filesystem::path& file, std::string& note,
                                                   const std::filesystem::path& dir = {});
// Removes `file` (e.g. it failed to open), saves, returns the new list.
std::vector<std::filesystem::path> remove_recent_file(const std::filesystem::path& file, std::string& note,
                                                      const std::filesystem::path& dir = {});

// ---- Settings the user chose, remembered between runs (settings.json in config_dir()).
struct EditorSettings {
  ViewportResolution preview = ViewportResolution::automatic;
  std::filesystem::path export_dir;  // the export dialog's last folder; empty: not chosen yet
  // Vertical orbit: false is Blender's (a drag up moves the camera down, as if the scene were
  // grabbed), true the other way.
  bool invert_vertical_orbit = false;
  bool operator==(const EditorSettings&) const = default;
};
std::filesystem::path settings_path(const std::filesystem::path& dir = {});
// Missing or unknown values give the defaults without a note (a newer editor's values).
EditorSettings load_editor_settings(std::string& note, const std::filesystem::path& dir = {});
void save_editor_settings(const EditorSettings& settings, std::string& note, const std::filesystem::path& dir = {});
// The export dialog's first folder when none was remembered: the user's Pictures folder
// (XDG_PICTURES_DIR, else ~/Pictures when it exists), else the home folder; never the project's
// folder, which is often a source repository.
std::filesystem::path default_export_dir();

// ---- Crash recovery. Each editor session autosaves its document, while it has unsaved
// changes, to files of its own in state_dir(): recovery-ID.glint (the scene),
// recovery-ID.json (the sidecar: the original path and base folder) and recovery-ID.lock,
// which the session holds locked while it runs (editor/recovery_lock.h). Saving the document
// deletes the first two, a clean exit all three. A recovery whose lock is free was left by a
// session that did not exit cleanly: at start every such one is offered. The files of editors
// from before per-session names (recovery.glint, recovery.json) are offered the same way, with
// recovery.lock as their lock.
struct Recovery {
  std::filesystem::path file;      // the recovery project
  std::filesystem::path original;  // the document's file when it was written; empty: untitled
  Scene scene;                     // the recovered scene, base_dir and asset paths as they were
  std::time_t written = 0;         // when it was autosaved (the file's modification time)
  // Held while the recovery is on offer (every copy shares it), so that no other editor
  // offers or deletes it meanwhile; let go when the last copy goes.
  std::shared_ptr<RecoveryLock> lock;
};
// The recoveries that sessions which did not exit cleanly left in `dir`, newest first, each
// locked by this process. Recoveries of running editors are skipped; so are files that cannot
// be read or are not Glint projects, each with a line in `notes` (they stay on disk). A
// session's leftovers with nothing to recover (a lock file, a sidecar) are deleted.
std::vector<Recovery> find_recoveries(std::vector<std::string>& notes, const std::filesystem::path& dir = {});
// Deletes the recovery's files (scene, sidecar, lock file).
void discard_recovery(const Recovery& recovery);
// A document holding the recovered scene, dirty: its path is the original file (if any), and
// when the original still opens, undo goes back to it.
Document open_recovery(const Recovery& recovery);

// This session's autosave: writes its recovery files at most every `interval_s` while the
// document is dirty and changed since the last write, and deletes them once the document is
// clean (saved). The lock and the files' name are made at the first write. Never touches
// another session's recovery (such as the ones offered at start). Call update() every frame.
class Autosave {
 public:
  explicit Autosave(std::filesystem::path dir = {}, double interval_s = 10);
  // Returns true when it wrote the recovery file this call.
  bool update(const Document& doc, double now_s);
  // Clean exit: deletes this session's recovery files and lock file. Without it (a crash, or
  // this object destroyed) the files stay, unlocked, to be offered at the next start.
  void finish();
  const std::string& last_error() const { return last_error_; }
  // This session's recovery project; empty before the first write.
  std::filesystem::path file() const;

 private:
  void delete_recovery_files();
  std::filesystem::path dir_;
  double interval_s_;
  double last_write_s_ = 0;
  bool attempted_ = false;
  bool wrote_ = false;
  std::optional<Scene> written_;
  std::optional<RecoveryLock> lock_;
  std::string last_error_;
};

}  // namespace glint
