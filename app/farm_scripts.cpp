#include "app/farm_scripts.h"

#include <optional>
#include <stdexcept>

#include "app/slurm_syntax.h"
#include "renderer/render_part.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

// A string as one single-quoted shell word (the strings hold no newline or NUL: checked).
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// The directives hold only fixed words, numbers and a checked partition name.
std::string sbatch_header(const FarmPlan& p, const std::string& name) {
  std::string s = "#!/bin/bash\n#SBATCH --job-name=" + name + "\n";
  if (!p.partition.empty()) s += "#SBATCH --partition=" + p.partition + "\n";
  return s + "#SBATCH --ntasks=1\n";
}

// sbatch's --output, literal but for the pattern `tail` (%a: the array index).
std::string log_option(const fs::path& dir, const std::string& tail) {
  const std::optional<std::string> logs = slurm_filename_literal((dir / "logs").string());
  if (!logs) throw std::invalid_argument((dir / "logs").string() + ": a backslash (farm_folder_problem)");
  return "--output=" + *logs + "/" + tail;
}

}  // namespace

std::vector<std::string> part_command(const FarmPlan& p, const fs::path& dir, int i) {
  std::vector<std::string> c = {p.glint, "render", p.project, "--samples",
                                format_sample_range(farm_part_range(p, i)), "-o", farm_part_file(dir, i).string()};
  if (p.width) c.insert(c.end(), {"--width", std::to_string(*p.width)});
  if (p.height) c.insert(c.end(), {"--height", std::to_string(*p.height)});
  return c;
}

// Task i renders part i: its range is computed by the script (bash's 64-bit arithmetic, exact for
// N <= 2^32 and K <= 100000), so the script has the same few lines for any K.
std::string part_script(const FarmPlan& p, const fs::path& dir) {
  std::string s = sbatch_header(p, "glint-part");
  s += "#SBATCH --array=0-" + std::to_string(p.parts - 1) + "\n";
  if (p.gpus_per_task > 0) s += "#SBATCH --gpus-per-task=" + std::to_string(p.gpus_per_task) + "\n";
  s += "# Part i is the samples floor(i*N/K) to floor((i+1)*N/K)-1 of the N-sample render.\nset -eu\n";
  s += "N=" + std::to_string(p.spp) + " K=" + std::to_string(p.parts) + " i=${SLURM_ARRAY_TASK_ID:-}\n";
  s += "if ! [[ $i =~ ^(0|[1-9][0-9]{0,5})$ ]] || (( i >= K )); then\n"
       "  echo \"glint farm: no part '$i'\" >&2\n  exit 2\nfi\n";
  s += "printf -v part '%s/part-%04d.exr' " + quoted((dir / "parts").string()) + " \"$i\"\n";
  s += "exec " + quoted(p.glint) + " render " + quoted(p.project) +
       " --samples \"$((i * N / K)):$(((i + 1) * N / K))\" -o \"$part\"";
  if (p.width) s += " --width " + std::to_string(*p.width);
  if (p.height) s += " --height " + std::to_string(*p.height);
  return s + "\n";
}

std::string merge_script(const FarmPlan& p, const fs::path& dir) {
  std::string s = sbatch_header(p, "glint-merge");
  s += "set -eu\nshopt -s nullglob\nparts=(" + quoted((dir / "parts").string()) + "/part-*.exr)\n";
  s += "exec " + quoted(p.glint) + " merge --spp " + std::to_string(p.spp) + " \"${parts[@]}\" -o " +
       quoted(p.output) + "\n";
  return s;
}

std::vector<std::string> part_submit_args(const fs::path& dir, const std::vector<int>& indices) {
  return {"sbatch", "--parsable", "--array=" + array_ranges(indices), log_option(dir, "part-%a.log"),
          (dir / "part.sh").string()};
}

std::vector<std::string> merge_submit_args(const fs::path& dir, const std::string& dependency) {
  std::vector<std::string> a = {"sbatch", "--parsable"};
  if (!dependency.empty()) a.push_back("--dependency=" + dependency);
  a.insert(a.end(), {log_option(dir, "merge.log"), (dir / "merge.sh").string()});
  return a;
}

}  // namespace glint
