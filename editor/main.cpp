// glint: the scene editor (GLFW + Dear ImGui, next issue) and `glint render` (headless).
#include <cstdio>
#include <string>

#include "editor/render_command.h"

namespace {

const char* const kHelp =
    "glint: a scene editor with a progressive GPU path tracer\n"
    "\n"
    "usage:\n"
    "  glint render PROJECT.glint -o OUT.{png,hdr,exr} [options]   headless final render\n"
    "  glint render --help                                        render options\n"
    "\n"
    "The interactive editor is not built yet; `glint render` is the way to render a project.\n";

}  // namespace

int main(int argc, char** argv) {
  std::string command = argc > 1 ? argv[1] : "";
  if (command == "render") return glint::run_render_command(argc - 2, argv + 2);
  if (command == "-h" || command == "--help" || command == "help") {
    std::fputs(kHelp, stdout);
    return 0;
  }
  std::fprintf(stderr, "glint: %s\n\n%s",
               command.empty() ? "no command given" : ("unknown command '" + command + "'").c_str(), kHelp);
  return 2;
}
