// Project files (.glint, JSON, format version 1; docs/DESIGN.md §6): load with full validation,
// save atomically (temporary file renamed over the old one), exact round trip.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "renderer/project_error.h"
#include "renderer/scene.h"

namespace glint {

// The file's size limit: at most kMaxProjectBytes, read only from a regular file. The limit
// admits the largest scene of scene_validation.h's limits as save_project writes it (about
// 160 MiB for 2^20 spheres, 370 MiB for 2^20 quads, with full-precision coordinates) with room
// for long names.
constexpr uintmax_t kMaxProjectBytes = uintmax_t(1) << 30;

// Reads, parses and validates; throws ProjectError on the first problem. Never returns a
// half-loaded scene. The returned scene's base_dir is the file's folder.
Scene load_project(const std::filesystem::path& file);

// The same from the text of a project file (the fuzz target's entry point): `file_label` names
// it in errors and base_dir resolves its asset paths.
Scene load_project_text(const std::string& text, const std::string& file_label,
                        const std::filesystem::path& base_dir, bool check_files = true);

// Parses a JSON document as a scene (unknown keys, wrong types, bad values are errors).
// `file_label` only names the source in errors. Image files are checked for existence and
// readability (relative to base_dir) when check_files is true: each is decoded (once, see
// renderer/texture_cache.h) and checked within kMaxImageBytes (renderer/scene_images.h).
// "format": "glint-project" and "version": 1 are required. Validates like validate_scene
// (scene_validation.h). The fields are those of scene_fields.h's tables.
Scene scene_from_json(const nlohmann::json& doc, const std::string& file_label,
                      const std::filesystem::path& base_dir, bool check_files = true);
// The same for a document that keeps its key order (errors then follow the document's order).
Scene scene_from_json(const nlohmann::ordered_json& doc, const std::string& file_label,
                      const std::filesystem::path& base_dir, bool check_files = true);

// The canonical JSON of a scene: every key written, in the order of docs/DESIGN.md's example
// (hence ordered_json; it converts to nlohmann::json implicitly), null for empty texture
// references, floats in their shortest exact form (0.1f as 0.1, 40.0f as 40), integers as
// integers.
// Non-finite floats (which validate_scene rejects) become null.
nlohmann::ordered_json scene_to_json(const Scene& scene);

// The exact text save_project writes for a scene that stays in scene.base_dir: 2-space indent,
// arrays of numbers on one line ("position": [0, 1, 5]), a trailing newline.
std::string project_file_text(const Scene& scene);

// The scene with base_dir set to new_base_dir and its relative asset paths (textures[].path,
// environment.texture) rewritten to point at the same files from there; absolute paths are
// kept. When both folders are the same (the same path, or the same after resolving symlinks)
// the paths are kept verbatim.
// The editor's "Save As" applies this to its document after save_project.
Scene rebase_asset_paths(const Scene& scene, const std::filesystem::path& new_base_dir);

// The scene with its absolute asset paths made relative to `folder` (with `../` where needed),
// so that a project moved or copied together with its assets keeps working; relative paths are
// kept. The `../` steps climb from `folder` with its symbolic links resolved, as the system
// resolves them when the file is opened. On POSIX systems every absolute path has such a form;
// one on another drive (Windows: another root name) has none and stays absolute.
Scene relative_asset_paths(const Scene& scene, const std::filesystem::path& folder);

// The text that save_project writes to `file`, without writing anything (the in-memory half of
// save_project; load_project_text is the other direction). Relative asset paths are rewritten
// relative to the file's folder when it differs from scene.base_dir, and absolute ones made
// relative to it (relative_asset_paths). Does not validate (the UI
// validates edits; the loader reports anything bad). Throws ProjectError (with the file name)
// with the JSON path of a string that is not valid UTF-8 (a texture path in a folder named in
// another encoding: JSON text cannot hold it).
std::string save_project_text(const Scene& scene, const std::filesystem::path& file);

// Writes save_project_text(scene, file) atomically (write_file_atomically, atomic_file.h: a
// temporary file beside the target, fsync, rename; through symbolic links, keeping the mode).
// Throws ProjectError (with the file name and the OS reason) on IO failure and for the
// problems of save_project_text; the old file is then unchanged and no temporary file is left.
void save_project(const Scene& scene, const std::filesystem::path& file);

}  // namespace glint
