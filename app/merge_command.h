// `glint merge`: render parts (glint render --samples A:B) into one image (renderer/render_part.h).
#pragma once

namespace glint {

// argv holds the arguments after "merge". Returns the exit code (0 merged, 1 the parts do not
// make a render or a file could not be read or written, 2 bad arguments).
int run_merge_command(int argc, char** argv);

}  // namespace glint
