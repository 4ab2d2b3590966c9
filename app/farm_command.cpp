#include "app/farm_command.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/command_line.h"
#include "renderer/atomic_file.h"
#include "renderer/render_part.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

const char* const kUsage =
    "usage: glint farm slurm PROJECT.glint --spp N --parts K -o OUT.{exr,png,hdr}\n"
    "                        [--width W] [--height H] [--partition P] [--gpus-per-task G]\n"
    "                        [--dry-run]\n"
    "       glint farm slurm -o OUT --resume [--dry-run]\n"
    "       glint farm status -o OUT\n"
    "\n"
    "Renders a project on a Slurm cluster in K parts of about N/K samples each: a job array\n"
    "whose task i runs `glint render PROJECT --samples A:B` (the samples A..B-1 of the\n"
    "N-sample render) and a job that runs `glint merge` once every part succeeded. The\n"
    "scripts, the plan (farm.json), the parts and Slurm's logs go to the folder OUT.farm/\n"
    "beside OUT; every node must see it, the project and glint at the same paths (a shared\n"
    "file system).\n"
    "  --spp N            samples per pixel of the whole render\n"
    "  --parts K          array tasks (1 to N)\n"
    "  --width W, --height H  the image size, as for glint render\n"
    "  --partition P      sbatch --partition\n"
    "  --gpus-per-task G  sbatch --gpus-per-task: each part renders on the GPU Slurm gives\n"
    "                     it (CUDA_VISIBLE_DEVICES; without one, Mesa's llvmpipe)\n"
    "  --dry-run          print the scripts and the sbatch commands; write and submit nothing\n"
    "  --resume           resubmit only the parts that have no valid file and are not queued\n"
    "                     or running, and a merge job after them\n"
    "status: each part done, queued, running or missing (from its file and squeue), and\n"
    "the merged image.\n"
    "Exit codes: 0 done, 1 sbatch failed or a file could not be read or written (status:\n"
    "parts are missing), 2 bad arguments.\n";

// The render as farm.json records it.
struct Plan {
  std::string project, output, glint;
  int64_t spp = 0;
  int parts = 0;
  std::optional<long> width, height;
  std::string partition;
  int gpus_per_task = 0;
  std::vector<std::string> job_ids;  // every array submitted, the first one first
  std::string merge_job;
};

struct Options {
  std::string command;  // slurm or status
  Plan plan;
  bool resume = false, dry_run = false;
};

fs::path farm_dir(const std::string& output) {
  fs::path out = fs::absolute(output);
  return out.parent_path() / (out.stem().string() + ".farm");
}

SampleRange part_range(const Plan& p, int i) {
  return {p.spp * i / p.parts, p.spp * (i + 1) / p.parts};
}

fs::path part_file(const fs::path& dir, int i) {
  char name[32];
  std::snprintf(name, sizeof name, "part-%04d.exr", i);
  return dir / "parts" / name;
}

std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

long parse_count(const std::string& option, const std::string& text, long lo, long hi) {
  try {
    size_t used = 0;
    const long v = std::stol(text, &used);
    if (used == text.size() && v >= lo && v <= hi) return v;
  } catch (const std::exception&) {
  }
  throw UsageError{option + " expects an integer from " + std::to_string(lo) + " to " + std::to_string(hi) +
                   ", got '" + text + "'"};
}

Options parse(int argc, char** argv) {
  Options o;
  if (argc < 1) throw UsageError{"give slurm or status"};
  o.command = argv[0];
  if (o.command != "slurm" && o.command != "status") throw UsageError{"unknown farm command '" + o.command + "'"};
  bool spp = false, parts = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError{a + " needs a value"};
      return argv[++i];
    };
    if (a == "-o" || a == "--output") o.plan.output = value();
    else if (a == "--spp") o.plan.spp = parse_count(a, value(), 1, 1L << 32), spp = true;
    else if (a == "--parts") o.plan.parts = static_cast<int>(parse_count(a, value(), 1, 100000)), parts = true;
    else if (a == "--width") o.plan.width = parse_count(a, value(), 1, 16384);
    else if (a == "--height") o.plan.height = parse_count(a, value(), 1, 16384);
    else if (a == "--partition") o.plan.partition = value();
    else if (a == "--gpus-per-task") o.plan.gpus_per_task = static_cast<int>(parse_count(a, value(), 1, 64));
    else if (a == "--resume") o.resume = true;
    else if (a == "--dry-run") o.dry_run = true;
    else if (!a.empty() && a[0] == '-') throw UsageError{"unknown option " + a};
    else if (o.plan.project.empty()) o.plan.project = a;
    else throw UsageError{"unexpected argument '" + a + "'"};
  }
  if (o.plan.output.empty()) throw UsageError{"no output given (-o OUT.exr|.png|.hdr)"};
  const std::string ext = fs::path(o.plan.output).extension().string();
  if (ext != ".png" && ext != ".hdr" && ext != ".exr")
    throw UsageError{"output '" + o.plan.output + "' must end in .png, .hdr or .exr"};
  if (o.command == "slurm" && !o.resume) {
    if (o.plan.project.empty()) throw UsageError{"no project given"};
    if (!spp) throw UsageError{"--spp N is needed"};
    if (!parts) throw UsageError{"--parts K is needed"};
    if (o.plan.parts > o.plan.spp) throw UsageError{"--parts " + std::to_string(o.plan.parts) +
                                                    " is more than --spp " + std::to_string(o.plan.spp)};
  } else if (!o.plan.project.empty() || spp || parts || o.plan.width || o.plan.height) {
    throw UsageError{std::string(o.resume ? "--resume" : "status") +
                     " takes the render from OUT.farm/farm.json: give only -o OUT"};
  }
  return o;
}

nlohmann::json to_json(const Plan& p) {
  nlohmann::json j = {{"project", p.project}, {"output", p.output}, {"glint", p.glint}, {"spp", p.spp},
                      {"parts", p.parts}, {"partition", p.partition}, {"gpus_per_task", p.gpus_per_task},
                      {"job_ids", p.job_ids}, {"merge_job", p.merge_job}};
  if (p.width) j["width"] = *p.width;
  if (p.height) j["height"] = *p.height;
  return j;
}

Plan read_plan(const fs::path& dir) {
  const fs::path file = dir / "farm.json";
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": no farm here (start one with glint farm slurm PROJECT ...)");
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    Plan p;
    p.project = j.at("project").get<std::string>();
    p.output = j.at("output").get<std::string>();
    p.glint = j.at("glint").get<std::string>();
    p.spp = j.at("spp").get<int64_t>();
    p.parts = j.at("parts").get<int>();
    p.partition = j.at("partition").get<std::string>();
    p.gpus_per_task = j.at("gpus_per_task").get<int>();
    p.job_ids = j.at("job_ids").get<std::vector<std::string>>();
    p.merge_job = j.at("merge_job").get<std::string>();
    if (j.contains("width")) p.width = j["width"].get<long>();
    if (j.contains("height")) p.height = j["height"].get<long>();
    if (p.spp < 1 || p.parts < 1 || p.parts > p.spp) throw std::runtime_error("spp or parts out of range");
    return p;
  } catch (const std::exception& e) {
    throw std::runtime_error(file.string() + ": not a valid farm plan (" + e.what() + ")");
  }
}

void write_text(const fs::path& file, const std::string& text) {
  write_state_file_atomically(file, text.data(), text.size());
}

std::string sbatch_header(const Plan& p, const std::string& name, const fs::path& log) {
  std::string s = "#!/bin/bash\n#SBATCH --job-name=" + name + "\n#SBATCH --output=" + log.string() + "\n";
  if (!p.partition.empty()) s += "#SBATCH --partition=" + p.partition + "\n";
  return s;
}

// Task i of the array renders part i; the same command line runs a part under any scheduler.
std::string part_command(const Plan& p, const fs::path& dir, int i) {
  std::string c = quoted(p.glint) + " render " + quoted(p.project) + " --samples " +
                  format_sample_range(part_range(p, i)) + " -o " + quoted(part_file(dir, i).string());
  if (p.width) c += " --width " + std::to_string(*p.width);
  if (p.height) c += " --height " + std::to_string(*p.height);
  return c;
}

std::string part_script(const Plan& p, const fs::path& dir) {
  std::string s = sbatch_header(p, "glint-part", dir / "logs" / "part-%a.log");
  s += "#SBATCH --array=0-" + std::to_string(p.parts - 1) + "\n#SBATCH --ntasks=1\n";
  if (p.gpus_per_task > 0) s += "#SBATCH --gpus-per-task=" + std::to_string(p.gpus_per_task) + "\n";
  s += "# Part i is the samples floor(i*N/K) to floor((i+1)*N/K)-1 of the N-sample render.\nset -eu\n";
  s += "case \"$SLURM_ARRAY_TASK_ID\" in\n";
  for (int i = 0; i < p.parts; ++i) s += "  " + std::to_string(i) + ") exec " + part_command(p, dir, i) + " ;;\n";
  s += "esac\necho \"glint farm: no part $SLURM_ARRAY_TASK_ID\" >&2\nexit 2\n";
  return s;
}

std::string merge_command(const Plan& p, const fs::path& dir) {
  return quoted(p.glint) + " merge --spp " + std::to_string(p.spp) + " \"${parts[@]}\" -o " + quoted(fs::absolute(p.output).string());
}

std::string merge_script(const Plan& p, const fs::path& dir) {
  std::string s = sbatch_header(p, "glint-merge", dir / "logs" / "merge.log");
  s += "#SBATCH --ntasks=1\nset -eu\nshopt -s nullglob\nparts=(" + quoted((dir / "parts").string()) + "/part-*.exr)\n";
  s += "exec " + merge_command(p, dir) + "\n";
  return s;
}

// Runs a command line and returns its standard output; throws with its output on failure.
std::string run_command(const std::string& command) {
  std::FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + command);
  std::string out;
  char buffer[4096];
  while (size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  const int status = ::pclose(pipe);
  if (status != 0) throw std::runtime_error(command + " failed:\n" + out);
  return out;
}

// sbatch --parsable prints "ID" or "ID;CLUSTER" (and perhaps warnings on other lines).
std::string submit(const std::string& arguments) {
  const std::string out = run_command("sbatch --parsable " + arguments);
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    const std::string id = line.substr(0, line.find(';'));
    if (!id.empty() && id.find_first_not_of("0123456789") == std::string::npos) return id;
  }
  throw std::runtime_error("sbatch printed no job id:\n" + out);
}

enum class PartState { done, queued, running, missing, invalid };

// Array tasks of the plan's jobs that Slurm still has (pending or running), by task id; empty
// where squeue is not installed or knows none of them.
std::vector<std::pair<int, std::string>> queued_tasks(const Plan& p) {
  std::vector<std::pair<int, std::string>> tasks;
  std::string out;
  for (const std::string& id : p.job_ids) {  // one by one: squeue refuses ids it has forgotten
    try {
      out += run_command("squeue -h -r -j " + id + " -o '%i %T'");
    } catch (const std::runtime_error&) {
    }
  }
  std::istringstream lines(out);
  std::string id, state;
  while (lines >> id >> state) {
    const size_t underscore = id.find('_');
    if (underscore == std::string::npos) continue;
    try {
      tasks.emplace_back(std::stoi(id.substr(underscore + 1)), state);
    } catch (const std::exception&) {
    }
  }
  return tasks;
}

std::vector<PartState> part_states(const Plan& p, const fs::path& dir, std::vector<std::string>* notes) {
  std::vector<PartState> states(static_cast<size_t>(p.parts), PartState::missing);
  for (const auto& [task, state] : queued_tasks(p))
    if (task >= 0 && task < p.parts) states[task] = state == "RUNNING" ? PartState::running : PartState::queued;
  for (int i = 0; i < p.parts; ++i) {
    const fs::path file = part_file(dir, i);
    std::error_code ec;
    if (!fs::exists(file, ec)) continue;
    try {
      const PartInfo info = read_part_header(file);
      if (info.range == part_range(p, i)) {
        states[i] = PartState::done;
        continue;
      }
      if (notes) notes->push_back(file.string() + ": samples " + format_sample_range(info.range) + ", not " +
                                  format_sample_range(part_range(p, i)));
    } catch (const std::exception& e) {
      if (notes) notes->push_back(e.what());
    }
    if (states[i] == PartState::missing) states[i] = PartState::invalid;
  }
  return states;
}

const char* state_name(PartState s) {
  switch (s) {
    case PartState::done: return "done";
    case PartState::queued: return "queued";
    case PartState::running: return "running";
    case PartState::missing: return "missing";
    case PartState::invalid: return "invalid";
  }
  return "?";
}

int farm_status(const Options& o) {
  const fs::path dir = farm_dir(o.plan.output);
  const Plan p = read_plan(dir);
  std::vector<std::string> notes;
  const std::vector<PartState> states = part_states(p, dir, &notes);
  int done = 0, failed = 0;
  for (int i = 0; i < p.parts; ++i) {
    std::printf("part %d  samples %-14s %s\n", i, format_sample_range(part_range(p, i)).c_str(), state_name(states[i]));
    done += states[i] == PartState::done;
    failed += states[i] == PartState::missing || states[i] == PartState::invalid;
  }
  for (const std::string& n : notes) std::printf("  %s\n", n.c_str());
  std::error_code ec;
  const bool merged = fs::exists(p.output, ec);
  std::printf("%d of %d parts done, %d to resubmit (glint farm slurm -o %s --resume); %s %s\n", done, p.parts,
              failed, p.output.c_str(), p.output.c_str(), merged ? "exists" : "not written yet");
  return done == p.parts ? 0 : 1;
}

int farm_slurm(Options o) {
  const fs::path dir = farm_dir(o.plan.output);
  Plan p;
  std::vector<int> todo;
  if (o.resume) {
    p = read_plan(dir);
    const std::vector<PartState> states = part_states(p, dir, nullptr);
    for (int i = 0; i < p.parts; ++i)
      if (states[i] == PartState::missing || states[i] == PartState::invalid) todo.push_back(i);
    if (todo.empty()) {
      std::fprintf(stderr, "glint farm: no part to resubmit (every part is done, queued or running)\n");
      return 0;
    }
  } else {
    p = o.plan;
    p.project = fs::weakly_canonical(fs::absolute(p.project)).string();
    p.output = fs::weakly_canonical(fs::absolute(p.output)).string();
    if (const auto problem = file_write_problem(p.output)) throw std::runtime_error(p.output + ": " + *problem);
    std::error_code ec;
    p.glint = fs::read_symlink("/proc/self/exe", ec).string();
    if (ec) throw std::runtime_error("cannot find the glint executable (/proc/self/exe): " + ec.message());
    if (!fs::is_regular_file(p.project, ec)) throw std::runtime_error(p.project + ": no such project file");
    if (fs::exists(dir, ec))
      throw std::runtime_error(dir.string() + " exists (an earlier farm render of " + p.output +
                               "): resume it with --resume, or remove the folder to start again");
    for (int i = 0; i < p.parts; ++i) todo.push_back(i);
  }
  std::string array;
  for (int i : todo) array += (array.empty() ? "" : ",") + std::to_string(i);
  const fs::path part_sh = dir / "part.sh", merge_sh = dir / "merge.sh";
  const std::string part_args = "--array=" + array + " " + quoted(part_sh.string());
  if (o.dry_run) {
    if (!o.resume) std::printf("# %s\n%s\n# %s\n%s\n", part_sh.c_str(), part_script(p, dir).c_str(),
                               merge_sh.c_str(), merge_script(p, dir).c_str());
    std::printf("sbatch --parsable %s\nsbatch --parsable --dependency=afterok:<array job id> %s\n",
                part_args.c_str(), quoted(merge_sh.string()).c_str());
    return 0;
  }
  if (!o.resume) {
    fs::create_directories(dir / "parts");
    fs::create_directories(dir / "logs");
    write_text(part_sh, part_script(p, dir));
    write_text(merge_sh, merge_script(p, dir));
  } else if (!p.merge_job.empty()) {
    // The old merge job waits for an array that failed: it would never run (or would fail).
    try {
      run_command("scancel " + p.merge_job);
    } catch (const std::runtime_error&) {
    }
  }
  const std::string job = submit(part_args);
  p.job_ids.push_back(job);
  p.merge_job.clear();
  write_text(dir / "farm.json", to_json(p).dump(2) + "\n");  // the parts' job, even if the next sbatch fails
  p.merge_job = submit("--dependency=afterok:" + job + " " + quoted(merge_sh.string()));
  write_text(dir / "farm.json", to_json(p).dump(2) + "\n");
  std::fprintf(stderr, "glint farm: submitted %zu part%s (job %s, array %s) and the merge (job %s) to %s; "
               "parts in %s\n", todo.size(), todo.size() == 1 ? "" : "s", job.c_str(), array.c_str(),
               p.merge_job.c_str(), p.output.c_str(), (dir / "parts").c_str());
  return 0;
}

}  // namespace

int run_farm_command(int argc, char** argv) {
  Options o;
  if (int code = parse_command_line("glint farm", kUsage, argc, argv, parse, o); code >= 0) return code;
  try {
    return o.command == "status" ? farm_status(o) : farm_slurm(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint farm: %s\n", e.what());
    return 1;
  }
}

}  // namespace glint
