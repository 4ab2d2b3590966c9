// Scenes to and from other renderers' files (docs/DESIGN.md, "Scene exchange"): Mitsuba 3 XML
// (renderer/mitsuba_scene.h) and pbrt-v4 scene files (renderer/pbrt_scene.h), chosen by the
// file's extension, with Glint's own .glint as the third format. What the other format cannot
// hold, or holds differently, is named in a warning; nothing is dropped silently.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "renderer/scene.h"

namespace glint {

enum class SceneFormat { glint, mitsuba, pbrt };

// By extension (case-insensitive): .glint, .xml (Mitsuba 3), .pbrt (pbrt-v4); nullopt otherwise.
std::optional<SceneFormat> scene_format_for(const std::filesystem::path& file);
const char* to_string(SceneFormat format);

// What an export writes that a Glint scene does not hold.
struct ExportOptions {
  int samples_per_pixel = 64;  // the sampler's count (a Glint render takes it from glint render --spp)
};

// A file an export writes besides the scene (a mesh the format cannot hold inline), with its
// path relative to the scene file's folder.
struct SideFile {
  std::string relative_path;
  std::string text;
};

struct ExportedScene {
  std::string text;
  std::vector<SideFile> side_files;
  std::vector<std::string> warnings;
};

struct ImportedScene {
  Scene scene;
  std::vector<std::string> warnings;
};

// Reads any of the three formats; the scene is validated as a project is (textures must exist).
// Throws ProjectError naming the file and, for XML and pbrt, the line and element.
ImportedScene import_scene(const std::filesystem::path& file);

// Writes `scene` to `file` in the format of its extension (atomically, like save_project), side
// files included, with asset paths relative to the file's folder. Returns the warnings. Throws
// ProjectError for an unknown extension or a failed write.
std::vector<std::string> export_scene(const Scene& scene, const std::filesystem::path& file,
                                      const ExportOptions& options = {});

// Shared by the formats' readers and writers.
namespace exchange {

// A quad as an affine map of the square [-1, 1]^2 (Mitsuba's rectangle): columns x, y, z and
// the origin. p0 = o - x - y, p1 = o - x + y, p2 = o + x - y, p3 = o + x + y; z is the unit
// normal cross(p1 - p0, p2 - p0), so the rectangle's front is the quad's.
struct QuadFrame {
  glm::dvec3 x, y, z, origin;
};
QuadFrame quad_frame(const std::array<glm::vec3, 4>& corners);
std::array<glm::vec3, 4> quad_corners(const QuadFrame& frame);

// True for the default uvs (0,0) (0,1) (1,0) (1,1).
bool has_default_uvs(const Quad& quad);

// A quad from a two-triangle mesh: 4 vertices, triangles that share one edge and together use
// every vertex. nullopt otherwise. `indices` are 6 vertex indices; uvs may be empty.
std::optional<Quad> quad_from_triangles(const std::vector<glm::vec3>& positions,
                                        const std::vector<glm::vec2>& uvs,
                                        const std::vector<int>& indices);

// "3 spheres" / "1 sphere"
std::string count_text(size_t count, const std::string& noun);

}  // namespace exchange

}  // namespace glint
