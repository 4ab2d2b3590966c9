// `glint render`: headless final render of a project to PNG, HDR or EXR.
#pragma once

namespace glint {

// argv excludes "glint" and "render". Returns the process exit code.
int run_render_command(int argc, char** argv);

}  // namespace glint
