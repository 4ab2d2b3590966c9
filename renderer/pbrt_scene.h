// pbrt-v4 scene files (docs/DESIGN.md, "Scene exchange"; the format of
// https://pbrt.org/fileformat-v4): the writer maps Glint's conventions onto pbrt's (a
// left-handed camera, fov along the shorter image axis, roughness as alpha without remapping,
// image v flipped, emission two-sided), the reader takes back what it writes and the common
// subset of other scenes, naming what it leaves out.
#pragma once

#include <filesystem>
#include <string>

#include "renderer/scene_exchange.h"

namespace glint {

// The text of `scene` (asset paths relative to the folder the file goes to). pbrt's textures
// and meshes are inline: no side files.
ExportedScene write_pbrt_scene(const Scene& scene, const std::string& stem, const ExportOptions& options);

// The scene of a pbrt file's text. Throws ProjectError(file_label, "line N: Directive", problem).
ImportedScene read_pbrt_scene(const std::string& text, const std::string& file_label,
                              const std::filesystem::path& base_dir);

}  // namespace glint
