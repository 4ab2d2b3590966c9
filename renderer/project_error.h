// The error type of project files and scene validation: a problem with the file it was found
// in and the JSON path of the value (docs/DESIGN.md §6).
#pragma once

#include <stdexcept>
#include <string>

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

}  // namespace glint
