// What `glint farm slurm` gives Slurm: the two batch scripts of a plan (part.sh, a job array
// whose task i renders part i; merge.sh, which merges the parts) and the sbatch command lines
// that submit them. No path goes into an #SBATCH line: the scripts single-quote them in their
// commands, and the log files are sbatch's --output argument (slurm_filename_literal). The plan's
// strings are checked first (farm_plan.h: no newline or NUL, no backslash in the farm folder).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "app/farm_plan.h"

namespace glint {

std::string part_script(const FarmPlan& plan, const std::filesystem::path& folder);
std::string merge_script(const FarmPlan& plan, const std::filesystem::path& folder);

// The command line task i runs (for --dry-run: the script computes the same).
std::vector<std::string> part_command(const FarmPlan& plan, const std::filesystem::path& folder, int i);

// sbatch --parsable --array=RANGES --output=LOGS/part-%a.log part.sh
std::vector<std::string> part_submit_args(const std::filesystem::path& folder, const std::vector<int>& indices);
// sbatch --parsable [--dependency=DEPENDENCY] --output=LOGS/merge.log merge.sh
std::vector<std::string> merge_submit_args(const std::filesystem::path& folder, const std::string& dependency);

}  // namespace glint
