// Project files (.glint, JSON, format version 1; docs/DESIGN.md §3): load with full validation,
// save atomically (temporary file renamed over the old one), exact round trip.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/scene.h"

namespace glint {

// One problem found in a project. what() reads "FILE: JSON_PATH: PROBLEM",
// e.g. "scenes/a.glint: spheres[3].radius: must be greater than 0 (got -1)"; an empty file or
// path is left out with its ": " (validate_scene's errors read "JSON_PATH: PROBLEM").
struct ProjectError : std::runtime_error {
  ProjectError(std::string file, std::string json_path, std::string problem);
  std::string file;
  std::string json_path;  // "" for whole-file problems (unreadable, not JSON)
  std::string problem;
};

// Limits of a project, checked on load and by validate_scene (docs/DESIGN.md §3 lists them).
//  - Film: at most kMaxFilmSide pixels per side (the GL_MAX_TEXTURE_SIZE of llvmpipe and common
//    GPUs) and kMaxFilmPixels in all. The renderer keeps kFilmBytesPerPixel of GPU memory per
//    pixel (two RGBA32F accumulation textures, two RGBA32F compensation textures and an RGBA8
//    display texture), so the largest film takes 4.25 GiB; a larger one is refused with its
//    memory estimate, never attempted.
//  - Spheres and quads: at most kMaxSpheres and kMaxQuads each (2^20; 10^6 spheres load). Their
//    std430 arrays (32 and 128 bytes an element) then stay within 128 MiB, the smallest
//    GL_MAX_SHADER_STORAGE_BLOCK_SIZE that OpenGL 4.5 allows. A longer array is refused before
//    any of its elements is read.
//  - The file: at most kMaxProjectBytes, read only from a regular file. The limit admits the
//    largest scene above as save_project writes it (about 160 MiB for 2^20 spheres, 370 MiB for
//    2^20 quads, with full-precision coordinates) with room for long names.
constexpr int kMaxFilmSide = 16384;
constexpr int64_t kMaxFilmPixels = int64_t(1) << 26;  // e.g. 8192 x 8192
constexpr int kFilmBytesPerPixel = 4 * 16 + 4;
constexpr size_t kMaxSpheres = size_t(1) << 20;
constexpr size_t kMaxQuads = size_t(1) << 20;
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
// "format": "glint-project" and "version": 1 are required. Validates like validate_scene.
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

// Validates a scene as the loader would (used after edits through the UI or the API).
// Returns the problems as ProjectErrors with an empty file name; empty when valid. A quad has
// zero area when either triangle's |cross(e1, e2)| <= 1e-12 * scale^2 (scale: the largest
// distance between two corners); camera.up is parallel when |sin| of its angle <= 1e-6.
std::vector<ProjectError> validate_scene(const Scene& scene, bool check_files = true);

// The problem with a width x height film (file name empty; JSON path film.width, film.height or
// film), or nullopt when it is within the limits above. Sizes too large say how much GPU memory
// they would take: "film.width: must be an integer in [1, 16384] (got 100000); a 100000x100000
// film would need 633.3 GiB of GPU buffers (68 bytes per pixel), the limit is 4.2 GiB
// (67108864 pixels, e.g. 8192x8192)".
std::optional<ProjectError> check_film_size(int64_t width, int64_t height);

// "335.3 GiB", "512.0 MiB": memory sizes in messages.
std::string bytes_text(double bytes);

// The text that save_project writes to `file`, without writing anything (the in-memory half of
// save_project; load_project_text is the other direction). Relative asset paths are rewritten
// relative to the file's folder when it differs from scene.base_dir. Does not validate (the UI
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
