// The interactive editor: a GLFW window (OpenGL 4.5 core) with Dear ImGui around the viewport.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "renderer/trace_backend.h"

namespace glint {

struct EditorOptions {
  std::filesystem::path project;     // empty: a new document (or the crash recovery on offer)
  std::filesystem::path screenshot;  // non-empty: save a PNG of the window and exit
  int frames = 0;                    // with --screenshot: after this many frames (0: see spp)
  int64_t spp = 0;                   // with --screenshot: once the viewport has this many spp
  int width = 1280, height = 800;    // window size in screen coordinates
  std::optional<TraceBackend> backend;  // nullopt: the automatic choice (renderer/backend_choice.h)
  std::string select;                // non-empty: the sphere or quad selected at start
};

// Runs until the window is closed (after the unsaved-changes prompt). Returns the exit code.
int run_editor(const EditorOptions& options);

// Parses the editor's arguments (argv without the program name). Returns nullopt and fills
// `error` on bad arguments.
std::optional<EditorOptions> parse_editor_options(int argc, char** argv, std::string& error);

}  // namespace glint
