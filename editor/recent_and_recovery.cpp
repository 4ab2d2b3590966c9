// Recent files, settings and crash recovery (see recent_and_recovery.h).
#include "editor/recent_and_recovery.h"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <set>
#include <stdexcept>
#include <system_error>

#include <nlohmann/json.hpp>

#include "renderer/atomic_file.h"
#include "renderer/json_fields.h"
#include "renderer/project_error.h"
#include "renderer/project_file.h"
#include "renderer/state_file.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

// $VAR/glint when VAR is set to an absolute path (the XDG rule), else ~/FALLBACK/glint.
fs::path xdg_dir(const char* var, const char* fallback) {
  if (const char* v = std::getenv(var); v && *v && fs::path(v).is_absolute()) return fs::path(v) / "glint";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / fallback / "glint";
  std::error_code ec;
  return fs::temp_directory_path(ec) / "glint";  // no home at all: still somewhere writable
}

// The file's text through read_state_file, parsed: nullopt when the file is missing (no
// note) or cannot be read or parsed (`note` says which, and what the editor does instead:
// `fallback`). `read_failed` tells a file that could not be read from one that is not JSON.
std::optional<json_fields::Json> read_json(const fs::path& file, const std::string& fallback, std::string& note,
                                           bool* read_failed = nullptr) {
  note.clear();
  if (read_failed) *read_failed = false;
  try {
    const std::optional<std::string> text = read_state_file(file);
    if (!text) return std::nullopt;
    return json_fields::parse_text(*text, file.string());
  } catch (const StateFileError& e) {
    if (read_failed) *read_failed = true;
    note = std::string(e.what()) + "; " + fallback;
  } catch (const ProjectError& e) {
    note = std::string(e.what()) + "; " + fallback;
  }
  return std::nullopt;
}

// write_state_file_atomically (renderer/atomic_file.h): a crash or a full disk mid-write never
// leaves half a file, and a link at the path is refused. Returns the problem ("FILE: PROBLEM"),
// or an empty string once written.
std::string write_text_atomic(const fs::path& file, const std::string& text) {
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  try {
    write_state_file_atomically(file, text.data(), text.size());
  } catch (const FileWriteError& e) {
    return e.what();
  }
  return {};
}

// The same for JSON; a path that is not valid UTF-8 (which JSON text cannot hold) is a problem.
std::string write_json_atomic(const fs::path& file, const nlohmann::json& j) {
  std::string text;
  try {
    text = j.dump(2) + "\n";
  } catch (const nlohmann::json::exception&) {
    return file.string() + ": a path to be written in it is not valid UTF-8";
  }
  return write_text_atomic(file, text);
}

fs::path absolute_normal(const fs::path& p) {
  std::error_code ec;
  fs::path a = fs::absolute(p, ec);
  return (ec ? p : a).lexically_normal();
}

void save_recent_files(const std::vector<fs::path>& files, std::string& note, const fs::path& dir) {
  nlohmann::json j;
  j["files"] = nlohmann::json::array();
  for (const fs::path& f : files) j["files"].push_back(f.string());
  if (std::string problem = write_json_atomic(recent_files_path(dir), j); !problem.empty())
    note = problem + "; the recent-files list is not saved";
}

// Parsed from recent.json's JSON.
std::vector<fs::path> recent_files_from(const json_fields::Json& j) {
  std::vector<fs::path> files;
  if (!j.is_object() || !j.contains("files") || !j["files"].is_array()) return files;
  for (const json_fields::Json& f : j["files"]) {
    if (!f.is_string() || f.get<std::string>().empty()) continue;
    const fs::path p = f.get<std::string>();
    if (std::find(files.begin(), files.end(), p) == files.end()) files.push_back(p);
    if (files.size() == kMaxRecentFiles) break;
  }
  return files;
}

// The list as add and remove change it: a file that could not be read is not overwritten
// (std::nullopt), one that is not valid JSON is (it holds nothing to keep).
std::optional<std::vector<fs::path>> recent_files_to_change(std::string& note, const fs::path& dir) {
  bool read_failed = false;
  const std::optional<json_fields::Json> j =
      read_json(recent_files_path(dir), "the recent-files list is not updated", note, &read_failed);
  if (read_failed) return std::nullopt;
  if (!note.empty()) note = recent_files_path(dir).string() + ": not a recent-files list; it is replaced";
  return j ? recent_files_from(*j) : std::vector<fs::path>{};
}

}  // namespace

fs::path config_dir(const fs::path& dir) {
  return dir.empty() ? xdg_dir("XDG_CONFIG_HOME", ".config") : dir;
}

fs::path state_dir(const fs::path& dir) {
  return dir.empty() ? xdg_dir("XDG_STATE_HOME", ".local/state") : dir;
}

fs::path recent_files_path(const fs::path& dir) { return config_dir(dir) / "recent.json"; }

std::vector<fs::path> load_recent_files(std::string& note, const fs::path& dir) {
  const std::optional<json_fields::Json> j =
      read_json(recent_files_path(dir), "the recent-files list is empty for now", note);
  return j ? recent_files_from(*j) : std::vector<fs::path>{};
}

std::vector<fs::path> add_recent_file(const fs::path& file, std::string& note, const fs::path& dir) {
  const fs::path p = absolute_normal(file);
  std::optional<std::vector<fs::path>> files = recent_files_to_change(note, dir);
  if (!files) return {p};
  std::erase(*files, p);
  files->insert(files->begin(), p);
  if (files->size() > kMaxRecentFiles) files->resize(kMaxRecentFiles);
  save_recent_files(*files, note, dir);
  return *files;
}

std::vector<fs::path> remove_recent_file(const fs::path& file, std::string& note, const fs::path& dir) {
  std::optional<std::vector<fs::path>> files = recent_files_to_change(note, dir);
  if (!files) return {};
  std::erase(*files, absolute_normal(file));
  std::erase(*files, file);
  save_recent_files(*files, note, dir);
  return *files;
}

namespace {

constexpr const char* kPreviewNames[] = {"auto", "full", "half", "quarter"};

}  // namespace

fs::path settings_path(const fs::path& dir) { return config_dir(dir) / "settings.json"; }

EditorSettings load_editor_settings(std::string& note, const fs::path& dir) {
  EditorSettings s;
  const std::optional<json_fields::Json> j = read_json(settings_path(dir), "using the default settings", note);
  if (!j || !j->is_object()) return s;
  if (auto p = j->find("preview"); p != j->end() && p->is_string())
    for (int i = 0; i < 4; ++i)
      if (p->get<std::string>() == kPreviewNames[i]) s.preview = static_cast<ViewportResolution>(i);
  if (auto e = j->find("export_dir"); e != j->end() && e->is_string()) s.export_dir = e->get<std::string>();
  if (auto o = j->find("invert_vertical_orbit"); o != j->end() && o->is_boolean())
    s.invert_vertical_orbit = o->get<bool>();
  return s;
}

void save_editor_settings(const EditorSettings& settings, std::string& note, const fs::path& dir) {
  nlohmann::json j;
  j["preview"] = kPreviewNames[static_cast<int>(settings.preview)];
  j["export_dir"] = settings.export_dir.string();
  j["invert_vertical_orbit"] = settings.invert_vertical_orbit;
  note = write_json_atomic(settings_path(dir), j);
  if (!note.empty()) note += "; the settings are not saved";
}

fs::path default_export_dir() {
  std::error_code ec;
  const char* home = std::getenv("HOME");
  const fs::path h = home && *home ? fs::path(home) : fs::path();
  // xdg-user-dirs writes XDG_PICTURES_DIR="$HOME/Pictures" into ~/.config/user-dirs.dirs.
  if (!h.empty()) {
    // Not Glint's file, but read the same careful way; a problem with it just means ~/Pictures.
    std::optional<std::string> text;
    try {
      text = read_state_file(config_dir().parent_path() / "user-dirs.dirs");
    } catch (const StateFileError&) {
    }
    if (text) {
      const std::string key = "XDG_PICTURES_DIR=\"";
      if (size_t at = text->find(key); at != std::string::npos) {
        size_t end = text->find('"', at + key.size());
        std::string v = text->substr(at + key.size(), end == std::string::npos ? std::string::npos : end - at - key.size());
        if (v.rfind("$HOME", 0) == 0) v = h.string() + v.substr(5);
        if (fs::is_directory(v, ec)) return v;
      }
    }
    if (fs::is_directory(h / "Pictures", ec)) return h / "Pictures";
    if (fs::is_directory(h, ec)) return h;
  }
  return fs::current_path(ec);
}

namespace {

constexpr const char* kRecoveryPrefix = "recovery-";
constexpr const char* kOldRecoveryStem = "recovery";  // the one fixed name of older editors

// The stem of a recovery file, sidecar or lock file named `name` ("recovery-ID" with 16 hex
// digits, or the old "recovery"), else empty.
std::string recovery_stem(const std::string& name) {
  const size_t dot = name.rfind('.');
  if (dot == std::string::npos) return {};
  const std::string stem = name.substr(0, dot), ext = name.substr(dot);
  if (ext != ".glint" && ext != ".json" && ext != ".lock") return {};
  if (stem == kOldRecoveryStem) return stem;
  const std::string prefix = kRecoveryPrefix;
  if (stem.size() != prefix.size() + 16 || stem.compare(0, prefix.size(), prefix) != 0) return {};
  for (size_t i = prefix.size(); i < stem.size(); ++i)
    if (!std::isxdigit(static_cast<unsigned char>(stem[i]))) return {};
  return stem;
}

fs::path with_extension(const fs::path& file, const char* ext) { return fs::path(file).replace_extension(ext); }

void remove_quietly(const fs::path& file) {
  std::error_code ec;
  fs::remove(file, ec);
}

std::time_t modification_time(const fs::path& file) {
  struct stat st {};
  return ::stat(file.c_str(), &st) == 0 ? st.st_mtime : 0;
}

// Writes the recovery project `file` and its sidecar, each atomically and never through a link.
// save_project_text rewrites relative asset paths to point from the recovery folder; the sidecar
// keeps the original folder so that find_recoveries can rebase them back. Throws
// std::runtime_error (ProjectError for a path save_project_text cannot write).
void write_recovery_files(const Document& doc, const fs::path& file) {
  const std::string text = save_project_text(doc.scene, file);
  // A problem reads "FILE: PROBLEM", FILE naming the recovery file or its sidecar.
  if (std::string problem = write_text_atomic(file, text); !problem.empty()) throw std::runtime_error(problem);
  std::error_code ec;
  nlohmann::json side;
  side["original"] = doc.path().empty() ? nlohmann::json(nullptr)
                                        : nlohmann::json(absolute_normal(doc.path()).string());
  side["base_dir"] = absolute_normal(doc.scene.base_dir.empty() ? fs::current_path(ec)
                                                                : doc.scene.base_dir)
                         .string();
  const fs::path sidecar = with_extension(file, ".json");
  if (std::string problem = write_json_atomic(sidecar, side); !problem.empty()) throw std::runtime_error(problem);
}

// The recovery `file`, read as untrusted input (a FIFO, a folder, a file over the project size
// limit or text that is not a Glint project is a problem, thrown as StateFileError or
// ProjectError). Its sidecar is optional: without it, or with a problem (added to `notes`), the
// scene stays based in the recovery folder, where its relative paths still resolve.
Recovery read_recovery(const fs::path& file, std::vector<std::string>& notes) {
  const std::optional<std::string> text = read_state_file(file, kMaxProjectBytes);
  if (!text) throw StateFileError(file, "was deleted meanwhile");
  Recovery r;
  r.file = file;
  r.written = modification_time(file);
  // Asset files are not required: a missing texture must not lose the user's work.
  r.scene = load_project_text(*text, file.string(), absolute_normal(file.parent_path()), false);
  std::string note;
  const std::optional<json_fields::Json> side =
      read_json(with_extension(file, ".json"), "asset paths are taken as relative to the recovery folder", note);
  if (!note.empty()) notes.push_back(note);
  if (side && side->is_object()) {
    if (side->contains("original") && (*side)["original"].is_string())
      r.original = (*side)["original"].get<std::string>();
    if (side->contains("base_dir") && (*side)["base_dir"].is_string())
      r.scene = rebase_asset_paths(r.scene, (*side)["base_dir"].get<std::string>());
  }
  return r;
}

}  // namespace

std::vector<Recovery> find_recoveries(std::vector<std::string>& notes, const fs::path& dir) {
  const fs::path folder = state_dir(dir);
  std::set<std::string> stems;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
    if (std::string stem = recovery_stem(it->path().filename().string()); !stem.empty()) stems.insert(stem);
  if (ec && ec != std::errc::no_such_file_or_directory)
    notes.push_back(folder.string() + ": cannot list the recovery folder: " + ec.message() + "; nothing is offered");
  std::vector<Recovery> found;
  for (const std::string& stem : stems) {
    const fs::path file = folder / (stem + ".glint");
    std::optional<RecoveryLock> lock;
    std::string problem;
    switch (RecoveryLock::try_claim(folder / (stem + ".lock"), lock, problem)) {
      case RecoveryLock::Claim::taken: break;
      case RecoveryLock::Claim::held_elsewhere: continue;  // a running editor's
      case RecoveryLock::Claim::gone: continue;            // deleted by another editor just now
      case RecoveryLock::Claim::refused:
        notes.push_back((folder / (stem + ".lock")).string() + ": " + problem + "; " + file.string() +
                        " is not offered for recovery");
        continue;
    }
    struct stat st {};
    if (::lstat(file.c_str(), &st) != 0 && errno == ENOENT) {
      // A session that ended with nothing to recover (or was stopped mid-cleanup).
      remove_quietly(with_extension(file, ".json"));
      lock->remove_and_release();
      continue;
    }
    try {
      Recovery r = read_recovery(file, notes);
      r.lock = std::make_shared<RecoveryLock>(std::move(*lock));
      found.push_back(std::move(r));
    } catch (const std::exception& e) {  // StateFileError, ProjectError: left on disk as it is
      notes.push_back(std::string(e.what()) + "; not offered for recovery");
    }
  }
  std::stable_sort(found.begin(), found.end(),
                   [](const Recovery& a, const Recovery& b) { return a.written > b.written; });
  return found;
}

void discard_recovery(const Recovery& recovery) {
  remove_quietly(recovery.file);
  remove_quietly(with_extension(recovery.file, ".json"));
  if (recovery.lock) recovery.lock->remove_and_release();
}

Document open_recovery(const Recovery& recovery) {
  std::error_code ec;
  if (!recovery.original.empty() && fs::exists(recovery.original, ec)) {
    try {
      Document doc(load_project(recovery.original), recovery.original);
      doc.scene = rebase_asset_paths(recovery.scene, doc.scene.base_dir);
      doc.end_frame(false);  // one undo step back to the file as saved
      return doc;
    } catch (const ProjectError&) {
      // The original no longer opens: fall through and keep the recovered scene alone.
    }
  }
  // Nothing saved to compare with: an empty baseline makes the recovered scene dirty.
  Scene baseline;
  baseline.base_dir = recovery.scene.base_dir;
  Document doc(baseline, recovery.original);
  doc.scene = recovery.scene;
  doc.end_frame(false);
  return doc;
}

Autosave::Autosave(fs::path dir, double interval_s) : dir_(std::move(dir)), interval_s_(interval_s) {}

fs::path Autosave::file() const {
  return lock_ ? with_extension(lock_->path(), ".glint") : fs::path();
}

void Autosave::delete_recovery_files() {
  if (!lock_) return;
  remove_quietly(file());
  remove_quietly(with_extension(lock_->path(), ".json"));
}

bool Autosave::update(const Document& doc, double now_s) {
  if (!doc.dirty()) {
    // Saved (or undone back to the saved state): the recovery this session wrote is stale.
    if (wrote_) {
      delete_recovery_files();
      wrote_ = false;
      written_.reset();
    }
    return false;
  }
  if (attempted_ && now_s - last_write_s_ < interval_s_) return false;
  if (written_ && *written_ == doc.scene) return false;
  attempted_ = true;
  last_write_s_ = now_s;  // after a failure too: retry at the next interval, not every frame
  try {
    if (!lock_) {
      const fs::path folder = state_dir(dir_);
      std::error_code ec;
      fs::create_directories(folder, ec);
      lock_.emplace(RecoveryLock::create_unique(folder, kRecoveryPrefix));
    }
    wrote_ = true;  // whatever got written must go once the document is clean
    write_recovery_files(doc, file());
  } catch (const std::exception& e) {
    last_error_ = e.what();
    return false;
  }
  last_error_.clear();
  written_ = doc.scene;
  return true;
}

void Autosave::finish() {
  delete_recovery_files();
  if (lock_) lock_->remove_and_release();
  lock_.reset();
  wrote_ = false;
  written_.reset();
}

}  // namespace glint
