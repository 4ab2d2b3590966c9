#include "renderer/scene_exchange.h"

#include <algorithm>
#include <cctype>

#include "renderer/atomic_file.h"
#include "renderer/mitsuba_scene.h"
#include "renderer/pbrt_scene.h"
#include "renderer/project_file.h"
#include "renderer/scene_validation.h"
#include "renderer/state_file.h"

namespace glint {

namespace fs = std::filesystem;

std::optional<SceneFormat> scene_format_for(const fs::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".glint") return SceneFormat::glint;
  if (ext == ".xml") return SceneFormat::mitsuba;
  if (ext == ".pbrt") return SceneFormat::pbrt;
  return std::nullopt;
}

const char* to_string(SceneFormat format) {
  switch (format) {
    case SceneFormat::glint: return "Glint project";
    case SceneFormat::mitsuba: return "Mitsuba 3 XML";
    case SceneFormat::pbrt: return "pbrt-v4";
  }
  return "?";
}

namespace {

SceneFormat format_or_throw(const fs::path& file) {
  if (const auto format = scene_format_for(file)) return *format;
  throw ProjectError(file.string(), "", "unknown scene format: the name must end in .glint, .xml (Mitsuba 3) or .pbrt (pbrt-v4)");
}

// The text of a scene file of another renderer, with the project file's size limit.
std::string read_scene_text(const fs::path& file) {
  try {
    if (auto text = read_state_file(file, kMaxProjectBytes)) return std::move(*text);
  } catch (const StateFileError& e) {
    throw ProjectError(file.string(), "", e.problem);
  }
  throw ProjectError(file.string(), "", "file not found");
}

}  // namespace

ImportedScene import_scene(const fs::path& file) {
  const SceneFormat format = format_or_throw(file);
  if (format == SceneFormat::glint) return {load_project(file), {}};
  const std::string text = read_scene_text(file);
  fs::path base = file.parent_path();
  if (base.empty()) base = ".";
  ImportedScene imported = format == SceneFormat::mitsuba ? read_mitsuba_scene(text, file.string(), base)
                                                          : read_pbrt_scene(text, file.string(), base);
  imported.scene.base_dir = base;
  // The project's own validation, image files included: what was read must load as a project.
  const std::vector<ProjectError> problems = validate_scene(imported.scene, true);
  if (!problems.empty())
    throw ProjectError(file.string(), problems.front().json_path, problems.front().problem);
  return imported;
}

std::vector<std::string> export_scene(const Scene& scene, const fs::path& file, const ExportOptions& options) {
  const SceneFormat format = format_or_throw(file);
  if (format == SceneFormat::glint) {
    save_project(scene, file);
    return {};
  }
  fs::path folder = file.parent_path();
  if (folder.empty()) folder = ".";
  const Scene here = rebase_asset_paths(scene, folder);
  const std::string stem = file.stem().string();
  const ExportedScene exported = format == SceneFormat::mitsuba ? write_mitsuba_scene(here, stem, options)
                                                                : write_pbrt_scene(here, stem, options);
  try {
    for (const SideFile& side : exported.side_files) {
      const fs::path path = folder / side.relative_path;
      fs::create_directories(path.parent_path());
      write_file_atomically(path, side.text.data(), side.text.size());
    }
    write_file_atomically(file, exported.text.data(), exported.text.size());
  } catch (const FileWriteError& e) {
    throw ProjectError(e.what(), "", "not written");
  } catch (const fs::filesystem_error& e) {
    throw ProjectError(file.string(), "", std::string("cannot create the mesh folder: ") + e.code().message());
  }
  return exported.warnings;
}

namespace exchange {

QuadFrame quad_frame(const std::array<glm::vec3, 4>& c) {
  const glm::dvec3 p0(c[0]), p1(c[1]), p2(c[2]), p3(c[3]);
  QuadFrame f;
  f.x = (p2 - p0) * 0.5;
  f.y = (p1 - p0) * 0.5;
  f.z = glm::normalize(glm::cross(p1 - p0, p2 - p0));
  f.origin = (p0 + p1 + p2 + p3) * 0.25;
  return f;
}

std::array<glm::vec3, 4> quad_corners(const QuadFrame& f) {
  return {glm::vec3(f.origin - f.x - f.y), glm::vec3(f.origin - f.x + f.y), glm::vec3(f.origin + f.x - f.y),
          glm::vec3(f.origin + f.x + f.y)};
}

bool has_default_uvs(const Quad& quad) { return quad.uvs == Quad{}.uvs; }

std::optional<Quad> quad_from_triangles(const std::vector<glm::vec3>& positions, const std::vector<glm::vec2>& uvs,
                                        const std::vector<int>& indices) {
  if (positions.size() != 4 || indices.size() != 6 || (!uvs.empty() && uvs.size() != 4)) return std::nullopt;
  for (int i : indices)
    if (i < 0 || i > 3) return std::nullopt;
  for (int first = 0; first < 2; ++first) {
    const int* a = &indices[first * 3];
    const int* b = &indices[(1 - first) * 3];
    for (int k = 0; k < 3; ++k) {
      // (p0, p1, p2) = a rotated by k; b must be a rotation of (p1, p3, p2).
      const int i0 = a[k], i1 = a[(k + 1) % 3], i2 = a[(k + 2) % 3];
      const int i3 = 6 - i0 - i1 - i2;  // the vertex a does not use (indices are 0..3)
      if (i0 == i1 || i1 == i2 || i0 == i2) return std::nullopt;
      for (int r = 0; r < 3; ++r) {
        const int want[3] = {i1, i3, i2};
        if (b[0] == want[r] && b[1] == want[(r + 1) % 3] && b[2] == want[(r + 2) % 3]) {
          Quad q;
          const int order[4] = {i0, i1, i2, i3};
          for (int c = 0; c < 4; ++c) {
            q.corners[c] = positions[order[c]];
            if (!uvs.empty()) q.uvs[c] = uvs[order[c]];
          }
          return q;
        }
      }
    }
  }
  return std::nullopt;
}

std::string count_text(size_t count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

}  // namespace exchange

}  // namespace glint
