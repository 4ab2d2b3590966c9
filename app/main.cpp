// glint: the scene editor (GLFW + Dear ImGui) and `glint render` (headless).
#include <cstdio>
#include <cstdlib>
#include <string>

#include "editor/editor_app.h"
#include "app/convert_command.h"
#include "app/farm_command.h"
#include "app/merge_command.h"
#include "app/render_command.h"
#include "renderer/build_info.h"

namespace {

const char* const kHelp =
    "glint: a scene editor with a progressive GPU path tracer\n"
    "\n"
    "usage:\n"
    "  glint [PROJECT.glint] [options]                            open the editor\n"
    "  glint render PROJECT.glint -o OUT.{png,hdr,exr} [options]   headless final render\n"
    "  glint render --help                                        render options\n"
    "  glint merge PART.exr... -o OUT.{exr,png,hdr}                join render parts\n"
    "  glint farm slurm PROJECT.glint --spp N --parts K -o OUT     render on a Slurm cluster\n"
    "  glint farm status -o OUT                                   the parts of a farm render\n"
    "  glint convert IN OUT                                       a scene between .glint, Mitsuba\n"
    "                                                             3 (.xml) and pbrt-v4 (.pbrt)\n"
    "  glint --version                                            the version and its commit\n"
#ifdef GLINT_WITH_EDITOR
    "\n"
    "Editor options (the editor needs a display; on a server use xvfb-run):\n"
    "  --size WxH           window size (default 1280x800)\n"
    "  --frames N           close after N frames, dropping unsaved changes (for scripts)\n"
    "  --screenshot FILE    save a PNG of the window after --frames N (default 60) or once\n"
    "                       the viewport has --spp N samples per pixel, then exit (such runs\n"
    "                       neither offer a crash recovery nor autosave)\n"
    "  --spp N              with --screenshot: take it once the viewport has N samples/pixel\n"
    "  --select NAME        select the sphere or quad named NAME at start (its gizmo shows)\n"
    "  --backend B          auto (the default: the faster on this device), fragment or\n"
    "                       compute: the path tracer's entry point (same image)\n"
    "\n"
    "Editor controls (Help > Controls in the editor lists them all):\n"
    "  left or right drag: orbit    middle or Shift+drag: pan    wheel: zoom\n"
    "  click: select       Ctrl+click: set the focus distance there\n"
    "  W A S D Q E: fly    F: frame the selection    Del: delete    Shift+D: duplicate\n"
    "  click a number field: type a value    File > Examples: example projects\n"
    "  G / R / T: move / rotate / scale gizmo (drag its arrows, rings, squares or circle)\n"
    "  Ctrl+Z / Ctrl+Shift+Z: undo / redo    Ctrl+N/O/S: new, open, save    Ctrl+Q: quit\n"
    "  Ctrl+B then drag: render region (samples only there)    Ctrl+Alt+B: clear it\n"
    "  drop an image on the window: texture of the selected object (.hdr/.exr: environment)\n"
#else
    "\n"
    "This glint was built without the editor (GLINT_BUILD_EDITOR=OFF): only the commands above.\n"
#endif
    ;

// The XDG Base Directory specification: a relative path in one of these is invalid and must be
// ignored. Unset here, for the whole process, so that the libraries Glint loads ignore it too
// (Mesa would otherwise put its shader cache in whatever folder a render starts in).
void ignore_relative_xdg_dirs() {
  for (const char* name : {"XDG_CACHE_HOME", "XDG_CONFIG_HOME", "XDG_STATE_HOME", "XDG_DATA_HOME"})
    if (const char* value = std::getenv(name); value && *value != '/') unsetenv(name);
}

}  // namespace

int main(int argc, char** argv) {
  ignore_relative_xdg_dirs();
  std::string command = argc > 1 ? argv[1] : "";
  if (command == "render") return glint::run_render_command(argc - 2, argv + 2);
  if (command == "merge") return glint::run_merge_command(argc - 2, argv + 2);
  if (command == "farm") return glint::run_farm_command(argc - 2, argv + 2);
  if (command == "convert") return glint::run_convert_command(argc - 2, argv + 2);
  if (command == "-h" || command == "--help" || command == "help") {
    std::fputs(kHelp, stdout);
    return 0;
  }
  if (command == "--version" || command == "-V") {
    std::printf("glint %s (commit %s)\n", glint::glint_version(), glint::glint_commit());
    return 0;
  }
#ifdef GLINT_WITH_EDITOR
  std::string error;
  auto options = glint::parse_editor_options(argc - 1, argv + 1, error);
  if (!options) {
    std::fprintf(stderr, "glint: %s\n\n%s", error.c_str(), kHelp);
    return 2;
  }
  return glint::run_editor(*options);
#else
  std::fprintf(stderr, "glint: built without the editor (GLINT_BUILD_EDITOR=OFF): only `glint render`, `glint merge`, `glint farm` and `glint convert` are available\n");
  return 2;
#endif
}
