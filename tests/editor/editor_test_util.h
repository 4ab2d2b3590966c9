// Helpers shared by the editor tests: a temporary folder and a validity assertion.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "renderer/scene_validation.h"
#include "tests/temp_dir.h"

namespace glint::test {

// All problems of validate_scene joined, "" when valid (so a failure shows them).
inline std::string problems(const Scene& scene, bool check_files = false) {
  std::string out;
  for (const ProjectError& e : validate_scene(scene, check_files)) out += std::string(e.what()) + "\n";
  return out;
}

// A real image from the committed example assets, copied to `to`.
inline void copy_asset(const std::string& name, const std::filesystem::path& to) {
  std::filesystem::create_directories(to.parent_path());
  std::filesystem::copy_file(std::filesystem::path(GLINT_SOURCE_DIR) / "projects/assets" / name, to,
                             std::filesystem::copy_options::overwrite_existing);
}

}  // namespace glint::test
