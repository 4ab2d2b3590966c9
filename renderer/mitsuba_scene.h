// Mitsuba 3 XML scenes (docs/DESIGN.md, "Scene exchange"): the writer follows the conventions
// that bench/tools/mitsuba_export.py established and the accuracy bench validated; the reader
// takes back what the writer writes and the common subset of hand-written scenes, naming what
// it leaves out.
#pragma once

#include <filesystem>
#include <string>

#include "renderer/scene_exchange.h"

namespace glint {

// The XML of `scene`, whose asset paths are relative to the folder the XML goes to; meshes
// (quads that are not a rectangle with default uvs) are side files "<stem>-meshes/quad-N.obj".
// The film size, sample count, seed and environment image are <default> parameters (resx,
// resy, spp, seed, envmap) that mitsuba's load_file can override.
ExportedScene write_mitsuba_scene(const Scene& scene, const std::string& stem, const ExportOptions& options);

// The scene of an XML file's text; `base_dir` resolves the file's relative paths (meshes,
// images). Throws ProjectError(file_label, "line N: <element ...>", problem).
ImportedScene read_mitsuba_scene(const std::string& text, const std::string& file_label,
                                 const std::filesystem::path& base_dir);

}  // namespace glint
