// `glint convert`: a scene from one format to another (renderer/scene_exchange.h).
#pragma once

namespace glint {

// argv holds the arguments after "convert". Returns the exit code (0 converted, possibly with
// warnings; 1 the input could not be read or the output written; 2 bad arguments).
int run_convert_command(int argc, char** argv);

}  // namespace glint
