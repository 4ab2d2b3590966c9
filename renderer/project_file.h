// Project files (.glint, JSON, format version 1; DESIGN.md §3): load with full validation, save
// atomically (temporary file renamed over the old one), exact round trip.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/scene.h"

namespace glint {

// One problem found in a project. message() reads "FILE: JSON_PATH: PROBLEM",
// e.g. "scenes/a.glint: spheres[3].radius: must be greater than 0 (got -1)".
struct ProjectError : std::runtime_error {
  ProjectError(std::string file, std::string json_path, std::string problem);
  std::string file;
  std::string json_path;  // "" for whole-file problems (unreadable, not JSON)
  std::string problem;
};

// Reads, parses and validates; throws ProjectError on the first problem. Never returns a
// half-loaded scene. The returned scene's base_dir is the file's folder.
Scene load_project(const std::filesystem::path& file);

// Parses a JSON document as a scene (unknown keys, wrong types, bad values are errors).
// `file_label` only names the source in errors. Image files are checked for existence and
// readability (relative to base_dir) when check_files is true.
Scene scene_from_json(const nlohmann::json& doc, const std::string& file_label,
                      const std::filesystem::path& base_dir, bool check_files = true);

// The canonical JSON of a scene: every key written, floats in their shortest exact form.
nlohmann::json scene_to_json(const Scene& scene);

// Validates a scene as the loader would (used after edits through the UI or the API).
// Returns the problems as ProjectErrors with an empty file name; empty when valid.
std::vector<ProjectError> validate_scene(const Scene& scene, bool check_files = true);

// Writes atomically. Relative asset paths are rewritten relative to the new file's folder when
// it differs from scene.base_dir. Throws ProjectError (with the file name) on IO failure.
void save_project(const Scene& scene, const std::filesystem::path& file);

}  // namespace glint
