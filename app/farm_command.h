// `glint farm`: a render split into sample-range parts on a Slurm cluster (a job array of
// `glint render --samples A:B` and a `glint merge` job that depends on it), its status, and
// resubmitting only the parts that failed. docs/DESIGN.md §9, README "Rendering on a cluster".
#pragma once

namespace glint {

// argv holds the arguments after "farm". Returns the exit code (0 done, 1 a failure of Slurm or
// of a file, 2 bad arguments).
int run_farm_command(int argc, char** argv);

}  // namespace glint
