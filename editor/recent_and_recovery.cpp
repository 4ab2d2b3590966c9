// Recent files and crash recovery (see recent_and_recovery.h).
#include "editor/recent_and_recovery.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <system_error>

#include <nlohmann/json.hpp>

#include "renderer/atomic_file.h"
#include "renderer/project_file.h"

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

std::optional<std::string> read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return std::nullopt;
  return text;
}

// The shared atomic writer (renderer/atomic_file.h): a crash or a full disk mid-write never
// leaves half a file. Returns the problem, or an empty string once written.
std::string write_text_atomic(const fs::path& file, const std::string& text) {
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  try {
    write_state_file_atomically(file, text.data(), text.size());
  } catch (const FileWriteError& e) {
    return e.problem;
  }
  return {};
}

fs::path absolute_normal(const fs::path& p) {
  std::error_code ec;
  fs::path a = fs::absolute(p, ec);
  return (ec ? p : a).lexically_normal();
}

void save_recent_files(const std::vector<fs::path>& files, const fs::path& dir) {
  nlohmann::json j;
  j["files"] = nlohmann::json::array();
  for (const fs::path& f : files) j["files"].push_back(f.string());
  write_text_atomic(recent_files_path(dir), j.dump(2) + "\n");
}

fs::path sidecar_path(const fs::path& dir) { return state_dir(dir) / "recovery.json"; }

}  // namespace

fs::path config_dir(const fs::path& dir) {
  return dir.empty() ? xdg_dir("XDG_CONFIG_HOME", ".config") : dir;
}

fs::path state_dir(const fs::path& dir) {
  return dir.empty() ? xdg_dir("XDG_STATE_HOME", ".local/state") : dir;
}

fs::path recent_files_path(const fs::path& dir) { return config_dir(dir) / "recent.json"; }

std::vector<fs::path> load_recent_files(const fs::path& dir) {
  std::vector<fs::path> files;
  const std::optional<std::string> text = read_text(recent_files_path(dir));
  if (!text) return files;
  const nlohmann::json j = nlohmann::json::parse(*text, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object() || !j.contains("files") || !j["files"].is_array()) return files;
  for (const nlohmann::json& f : j["files"]) {
    if (!f.is_string() || f.get<std::string>().empty()) continue;
    const fs::path p = f.get<std::string>();
    if (std::find(files.begin(), files.end(), p) == files.end()) files.push_back(p);
    if (files.size() == kMaxRecentFiles) break;
  }
  return files;
}

std::vector<fs::path> add_recent_file(const fs::path& file, const fs::path& dir) {
  const fs::path p = absolute_normal(file);
  std::vector<fs::path> files = load_recent_files(dir);
  std::erase(files, p);
  files.insert(files.begin(), p);
  if (files.size() > kMaxRecentFiles) files.resize(kMaxRecentFiles);
  save_recent_files(files, dir);
  return files;
}

std::vector<fs::path> remove_recent_file(const fs::path& file, const fs::path& dir) {
  std::vector<fs::path> files = load_recent_files(dir);
  std::erase(files, absolute_normal(file));
  std::erase(files, file);
  save_recent_files(files, dir);
  return files;
}

namespace {

constexpr const char* kPreviewNames[] = {"auto", "full", "half", "quarter"};

}  // namespace

fs::path settings_path(const fs::path& dir) { return config_dir(dir) / "settings.json"; }

EditorSettings load_editor_settings(const fs::path& dir) {
  EditorSettings s;
  const std::optional<std::string> text = read_text(settings_path(dir));
  if (!text) return s;
  const nlohmann::json j = nlohmann::json::parse(*text, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object()) return s;
  if (auto p = j.find("preview"); p != j.end() && p->is_string())
    for (int i = 0; i < 4; ++i)
      if (p->get<std::string>() == kPreviewNames[i]) s.preview = static_cast<ViewportResolution>(i);
  if (auto e = j.find("export_dir"); e != j.end() && e->is_string()) s.export_dir = e->get<std::string>();
  return s;
}

void save_editor_settings(const EditorSettings& settings, const fs::path& dir) {
  nlohmann::json j;
  j["preview"] = kPreviewNames[static_cast<int>(settings.preview)];
  j["export_dir"] = settings.export_dir.string();
  write_text_atomic(settings_path(dir), j.dump(2) + "\n");
}

fs::path default_export_dir() {
  std::error_code ec;
  const char* home = std::getenv("HOME");
  const fs::path h = home && *home ? fs::path(home) : fs::path();
  // xdg-user-dirs writes XDG_PICTURES_DIR="$HOME/Pictures" into ~/.config/user-dirs.dirs.
  if (!h.empty()) {
    if (auto text = read_text(config_dir().parent_path() / "user-dirs.dirs")) {
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

fs::path recovery_file_path(const fs::path& dir) { return state_dir(dir) / "recovery.glint"; }

void write_recovery(const Document& doc, const fs::path& dir) {
  const fs::path file = recovery_file_path(dir);
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  // save_project rewrites relative asset paths to point from the recovery folder; the sidecar
  // keeps the original folder so find_recovery can rebase them back.
  save_project(doc.scene, file);
  nlohmann::json side;
  side["original"] = doc.path().empty() ? nlohmann::json(nullptr)
                                        : nlohmann::json(absolute_normal(doc.path()).string());
  side["base_dir"] = absolute_normal(doc.scene.base_dir.empty() ? fs::current_path(ec)
                                                                : doc.scene.base_dir)
                         .string();
  if (const std::string problem = write_text_atomic(sidecar_path(dir), side.dump(2) + "\n");
      !problem.empty())
    throw ProjectError(sidecar_path(dir).string(), "", "cannot write the recovery sidecar: " + problem);
}

std::optional<Recovery> find_recovery(const fs::path& dir) {
  const fs::path file = recovery_file_path(dir);
  const std::optional<std::string> text = read_text(file);
  if (!text) return std::nullopt;
  Recovery r;
  r.file = file;
  try {
    const nlohmann::ordered_json doc = nlohmann::ordered_json::parse(*text);
    // Asset files are not required: a missing texture must not lose the user's work.
    r.scene = scene_from_json(doc, file.string(), absolute_normal(file.parent_path()), false);
  } catch (const std::exception&) {
    return std::nullopt;  // a torn or foreign file: nothing to offer
  }
  // The sidecar is optional: without it the scene stays based in the recovery folder, where
  // its relative paths still resolve.
  if (const std::optional<std::string> side_text = read_text(sidecar_path(dir))) {
    const nlohmann::json side = nlohmann::json::parse(*side_text, nullptr, false);
    if (side.is_object()) {
      if (side.contains("original") && side["original"].is_string())
        r.original = side["original"].get<std::string>();
      if (side.contains("base_dir") && side["base_dir"].is_string())
        r.scene = rebase_asset_paths(r.scene, side["base_dir"].get<std::string>());
    }
  }
  return r;
}

void discard_recovery(const fs::path& dir) {
  std::error_code ec;
  fs::remove(recovery_file_path(dir), ec);
  fs::remove(sidecar_path(dir), ec);
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

bool Autosave::update(const Document& doc, double now_s) {
  if (!doc.dirty()) {
    // Saved (or undone back to the saved state): the recovery this session wrote is stale.
    if (wrote_) {
      discard_recovery(dir_);
      wrote_ = false;
      written_.reset();
    }
    return false;
  }
  if (attempted_ && now_s - last_write_s_ < interval_s_) return false;
  if (written_ && *written_ == doc.scene) return false;
  attempted_ = true;
  last_write_s_ = now_s;  // after a failure too: retry at the next interval, not every frame
  wrote_ = true;          // whatever got written must go once the document is clean
  try {
    write_recovery(doc, dir_);
  } catch (const std::exception& e) {
    last_error_ = e.what();
    return false;
  }
  last_error_.clear();
  written_ = doc.scene;
  return true;
}

void Autosave::finish() {
  if (wrote_) discard_recovery(dir_);  // an offered recovery left unanswered stays for next time
  wrote_ = false;
  written_.reset();
}

}  // namespace glint
