#include "app/farm_command.h"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "app/command_line.h"
#include "app/farm_parts.h"
#include "app/farm_plan.h"
#include "app/farm_scripts.h"
#include "app/render_size.h"
#include "app/run_program.h"
#include "app/slurm_syntax.h"
#include "renderer/atomic_file.h"
#include "renderer/image.h"
#include "renderer/project_file.h"
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
    "file system). Paths with a newline, and a farm folder with a backslash, are refused.\n"
    "  --spp N            samples per pixel of the whole render\n"
    "  --parts K          array tasks (1 to N, at most 100000)\n"
    "  --width W, --height H  the image size, as for glint render\n"
    "  --partition P      sbatch --partition: names of letters, digits, '_', '-' and '.',\n"
    "                     separated by commas\n"
    "  --gpus-per-task G  sbatch --gpus-per-task: each part renders on the GPU Slurm gives\n"
    "                     it (CUDA_VISIBLE_DEVICES; without one, Mesa's llvmpipe)\n"
    "  --dry-run          print the scripts, each part's command and the sbatch commands;\n"
    "                     write and submit nothing\n"
    "  --resume           resubmit the parts that are missing, invalid or stale and not\n"
    "                     queued or running, and a merge job after them; where there are\n"
    "                     none, a merge job alone if none is queued and OUT is not written\n"
    "farm.json is written before anything is submitted: after a failed sbatch, --resume\n"
    "submits what is missing.\n"
    "status: each part done, queued, running, missing, invalid (not a part of its range) or\n"
    "stale (a part of the project as it was: the parts are checked against the project as it is\n"
    "now, as glint merge checks them against each other), and the merged image.\n"
    "Exit codes: 0 done, 1 sbatch failed or a file could not be read or written (status:\n"
    "parts are not done), 2 bad arguments.\n";

// sbatch takes an argument of at most 128 KiB; a resubmission of scattered parts is split into
// arrays of at most this many characters of indices.
constexpr size_t kMaxArrayChars = 16384;

struct Options {
  std::string command;  // slurm or status
  FarmPlan plan;
  bool spp_given = false, parts_given = false;
  bool resume = false, dry_run = false;
};

// ---- Parsing: a table of the options (as glint render's), then the checks of them together.

// A path that goes into a script: one line, and (the farm folder) no backslash.
void check_script_path(const std::string& what, const std::string& path) {
  if (const auto problem = script_text_problem(path)) throw UsageError{what + " " + *problem};
}

using Flag = void (*)(Options&);
const std::pair<const char*, Flag> kFlags[] = {
    {"--resume", [](Options& o) { o.resume = true; }},
    {"--dry-run", [](Options& o) { o.dry_run = true; }},
};

// An option with a value: (options, the option as typed, its value).
using Text = const std::string&;
using Setter = void (*)(Options&, Text, Text);
const std::pair<const char*, Setter> kValueOptions[] = {
    {"-o", [](Options& o, Text, Text v) { o.plan.output = v; }},
    {"--output", [](Options& o, Text, Text v) { o.plan.output = v; }},
    {"--spp",
     [](Options& o, Text a, Text v) {
       o.plan.spp = parse_integer_option(a, v, 1, 1L << 32);
       o.spp_given = true;
     }},
    {"--parts",
     [](Options& o, Text a, Text v) {
       o.plan.parts = static_cast<int>(parse_integer_option(a, v, 1, kMaxFarmParts));
       o.parts_given = true;
     }},
    {"--width", [](Options& o, Text a, Text v) { o.plan.width = parse_integer_option(a, v, 1, 16384); }},
    {"--height", [](Options& o, Text a, Text v) { o.plan.height = parse_integer_option(a, v, 1, 16384); }},
    {"--partition",
     [](Options& o, Text, Text v) {
       o.plan.partition = v;
       if (const auto problem = partition_problem(o.plan.partition))
         throw UsageError{"--partition '" + o.plan.partition + "': " + *problem};
     }},
    {"--gpus-per-task",
     [](Options& o, Text a, Text v) {
       o.plan.gpus_per_task = static_cast<int>(parse_integer_option(a, v, 1, kMaxGpusPerTask));
     }},
};

// Reads argv[i] (and its value, advancing i) into `o`.
void parse_argument(Options& o, int argc, char** argv, int& i) {
  if (parse_table_option(o, kFlags, kValueOptions, argc, argv, i)) return;
  const std::string a = argv[i];
  if (!o.plan.project.empty()) throw UsageError{"unexpected argument '" + a + "'"};
  o.plan.project = a;
}

// The output, and its farm folder beside it: both go into the scripts.
void check_output(const Options& o) {
  if (o.plan.output.empty()) throw UsageError{"no output given (-o OUT.exr|.png|.hdr)"};
  if (const auto problem = output_format_problem(o.plan.output))
    throw UsageError{"output '" + o.plan.output + "' " + *problem};
  check_script_path("-o", o.plan.output);
  if (const auto problem = farm_folder_problem(farm_folder(o.plan.output)))
    throw UsageError{"-o: the farm folder " + farm_folder(o.plan.output).string() + " " + *problem};
}

// Whether anything of the render itself is given (which only a new farm takes).
bool render_options_given(const Options& o) {
  return !o.plan.project.empty() || o.spp_given || o.parts_given || o.plan.width || o.plan.height ||
         !o.plan.partition.empty() || o.plan.gpus_per_task;
}

// A new farm needs the project, --spp and --parts; --resume and status take the render from
// farm.json and nothing of it from the command line.
void check_render_options(const Options& o) {
  if (o.command != "slurm" || o.resume) {
    if (render_options_given(o))
      throw UsageError{std::string(o.resume ? "--resume" : "status") +
                       " takes the render from OUT.farm/farm.json: give only -o OUT"};
    return;
  }
  if (o.plan.project.empty()) throw UsageError{"no project given"};
  check_script_path("the project path", o.plan.project);
  if (!o.spp_given) throw UsageError{"--spp N is needed"};
  if (!o.parts_given) throw UsageError{"--parts K is needed"};
  if (o.plan.parts > o.plan.spp)
    throw UsageError{"--parts " + std::to_string(o.plan.parts) + " is more than --spp " + std::to_string(o.plan.spp)};
}

Options parse(int argc, char** argv) {
  Options o;
  if (argc < 1) throw UsageError{"give slurm or status"};
  o.command = argv[0];
  if (o.command != "slurm" && o.command != "status") throw UsageError{"unknown farm command '" + o.command + "'"};
  for (int i = 1; i < argc; ++i) parse_argument(o, argc, argv, i);
  check_output(o);
  check_render_options(o);
  return o;
}

// ---- Running: status, a new farm, a resumed one.

// The job id sbatch --parsable printed ("ID" or "ID;CLUSTER", perhaps after warnings); throws
// with sbatch's output when it failed.
std::string submit(const std::vector<std::string>& args) {
  const ProgramResult r = run_program(args);
  if (r.exit_code == 0) {
    size_t start = 0;
    while (start < r.output.size()) {
      size_t end = r.output.find('\n', start);
      if (end == std::string::npos) end = r.output.size();
      const std::string line = r.output.substr(start, end - start);
      const std::string id = line.substr(0, line.find(';'));
      if (!job_id_problem(id)) return id;
      start = end + 1;
    }
  }
  std::string out = r.output.size() > 2000 ? r.output.substr(0, 2000) + "..." : r.output;
  while (!out.empty() && out.back() == '\n') out.pop_back();
  throw std::runtime_error(shell_words(args) + (r.exit_code == 0 ? " printed no job id" : " failed (exit " +
                           std::to_string(r.exit_code) + ")") + (out.empty() ? "" : ":\n" + out));
}

void write_text(const fs::path& file, const std::string& text) {
  write_state_file_atomically(file, text.data(), text.size());
}

// Writes what the plan's jobs need: the folders (a resume recreates removed ones), the scripts
// and farm.json.
void write_farm(const FarmPlan& p, const fs::path& dir) {
  fs::create_directories(dir / "parts");
  fs::create_directories(dir / "logs");
  write_text(dir / "part.sh", part_script(p, dir));
  write_text(dir / "merge.sh", merge_script(p, dir));
  write_text(farm_plan_file(dir), farm_plan_json(p));
}

FarmPlan load_plan(const fs::path& dir) {
  std::optional<FarmPlan> p = read_farm_plan(dir);
  if (!p)
    throw std::runtime_error(farm_plan_file(dir).string() + ": no farm here (start one with glint farm slurm PROJECT ...)");
  return *p;
}

int farm_status(const Options& o) {
  const fs::path dir = farm_folder(o.plan.output);
  const FarmPlan p = load_plan(dir);
  const std::vector<PartInfo> expected = expected_parts(p);
  const QueueState queue = query_queue(p);
  std::vector<std::string> notes;
  if (!queue.known) notes.push_back("the queue is unknown (" + queue.problem + "): parts without a file are listed as missing");
  const std::vector<PartState> states = part_states(p, dir, queue, expected, notes);
  int done = 0, again = 0;
  for (int i = 0; i < p.parts; ++i) {
    std::printf("part %d  samples %-14s %s\n", i, format_sample_range(farm_part_range(p, i)).c_str(),
                part_state_name(states[i]));
    done += states[i] == PartState::done;
    again += needs_render(states[i]);
  }
  for (const std::string& n : notes) std::printf("  %s\n", n.c_str());
  std::error_code ec;
  const bool merged = fs::exists(p.output, ec);
  std::printf("%d of %d parts done, %d to resubmit (glint farm slurm -o %s --resume); %s %s\n", done, p.parts,
              again, p.output.c_str(), p.output.c_str(), merged ? "exists" : "not written yet");
  return done == p.parts ? 0 : 1;
}

// A new farm: the plan from the command line, checked against the project before anything is
// written.
FarmPlan new_plan(const Options& o, const fs::path& dir) {
  FarmPlan p = o.plan;
  p.project = fs::weakly_canonical(fs::absolute(p.project)).string();
  p.output = fs::weakly_canonical(fs::absolute(p.output)).string();
  std::error_code ec;
  p.glint = fs::read_symlink("/proc/self/exe", ec).string();
  if (ec) throw std::runtime_error("cannot find the glint executable (/proc/self/exe): " + ec.message());
  for (const auto& [what, path] : {std::pair{"the project", p.project}, {"the output", p.output}, {"glint's path", p.glint}})
    if (const auto problem = script_text_problem(path)) throw std::runtime_error(std::string(what) + " " + path + " " + *problem);
  if (const auto problem = file_write_problem(p.output)) throw std::runtime_error(p.output + ": " + *problem);
  if (!fs::is_regular_file(p.project, ec)) throw std::runtime_error(p.project + ": no such project file");
  render_size(p.width, p.height, load_project(p.project).film);  // a bad project or size fails now
  if (fs::exists(fs::symlink_status(dir, ec))) {
    if (fs::exists(farm_plan_file(dir), ec))
      throw std::runtime_error(dir.string() + " exists (an earlier farm render of " + p.output +
                               "): resume it with --resume, or remove the folder to start again");
    throw std::runtime_error(dir.string() + " exists and holds no farm.json: remove it or choose another -o");
  }
  return p;
}

// Submits the parts `todo` (in arrays of at most kMaxArrayChars of indices) and a merge job
// after them and after `old_arrays` (arrays of earlier submissions still queued: their tasks
// must end first, and one of them may have failed, so afterany). Records every job id in
// farm.json as soon as sbatch gives it.
void submit_farm(FarmPlan& p, const fs::path& dir, const std::vector<int>& todo,
                 const std::vector<std::string>& old_arrays) {
  std::vector<std::string> arrays;
  std::string summary;
  for (const std::vector<int>& group : split_array(todo, kMaxArrayChars)) {
    std::string job;
    try {
      job = submit(part_submit_args(dir, group));
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(std::string(e.what()) + "\n" +
                               (arrays.empty() && p.job_ids.empty() ? "nothing is submitted; " : "") +
                               "the plan is in " + farm_plan_file(dir).string() + ": glint farm slurm -o " +
                               p.output + " --resume submits what is missing");
    }
    arrays.push_back(job);
    p.job_ids.push_back(job);
    write_text(farm_plan_file(dir), farm_plan_json(p));
    summary += (summary.empty() ? "" : "; ") + ("job " + job + ", array " + array_ranges(group));
  }
  try {
    p.merge_job = submit(merge_submit_args(dir, dependency_list(arrays, old_arrays)));
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string(e.what()) + "\nthe parts are submitted (" + summary +
                             "), the merge is not: glint farm slurm -o " + p.output + " --resume submits it");
  }
  write_text(farm_plan_file(dir), farm_plan_json(p));
  if (todo.empty())
    std::fprintf(stderr, "glint farm: submitted the merge (job %s) to %s\n", p.merge_job.c_str(), p.output.c_str());
  else
    std::fprintf(stderr, "glint farm: submitted %zu part%s (%s) and the merge (job %s) to %s; parts in %s\n",
                 todo.size(), todo.size() == 1 ? "" : "s", summary.c_str(), p.merge_job.c_str(), p.output.c_str(),
                 (dir / "parts").c_str());
}

void print_dry_run(const FarmPlan& p, const fs::path& dir, const std::vector<int>& todo, bool scripts,
                   const std::vector<std::string>& old_arrays) {
  if (scripts) {
    std::printf("# %s\n%s\n# %s\n%s\n", (dir / "part.sh").c_str(), part_script(p, dir).c_str(),
                (dir / "merge.sh").c_str(), merge_script(p, dir).c_str());
    // Each part's command line (the first and last ten of many).
    for (int i = 0; i < p.parts; ++i) {
      if (p.parts > 20 && i == 10) {
        std::printf("# parts 10 to %d likewise\n", p.parts - 11);
        i = p.parts - 10;
      }
      std::printf("# part %d: %s\n", i, shell_words(part_command(p, dir, i)).c_str());
    }
  }
  std::vector<std::string> arrays;
  for (const std::vector<int>& group : split_array(todo, kMaxArrayChars)) {
    std::printf("%s\n", shell_words(part_submit_args(dir, group)).c_str());
    arrays.push_back("<array job id>");
  }
  std::printf("%s\n", shell_words(merge_submit_args(dir, dependency_list(arrays, old_arrays))).c_str());
}

int farm_slurm(const Options& o) {
  const fs::path dir = farm_folder(o.plan.output);
  if (!o.resume) {
    FarmPlan p = new_plan(o, dir);
    std::vector<int> todo;
    for (int i = 0; i < p.parts; ++i) todo.push_back(i);
    if (o.dry_run) {
      print_dry_run(p, dir, todo, true, {});
      return 0;
    }
    write_farm(p, dir);  // before sbatch: after a failed submission --resume finds the plan
    submit_farm(p, dir, todo, {});
    return 0;
  }

  FarmPlan p = load_plan(dir);
  const std::vector<PartInfo> expected = expected_parts(p);
  const QueueState queue = query_queue(p);
  if (!queue.known)
    throw std::runtime_error("cannot tell which parts Slurm still has (" + queue.problem + "): nothing resubmitted");
  std::vector<std::string> notes;
  const std::vector<PartState> states = part_states(p, dir, queue, expected, notes);
  for (const std::string& n : notes) std::fprintf(stderr, "glint farm: %s\n", n.c_str());
  std::vector<int> todo;
  for (int i = 0; i < p.parts; ++i)
    if (needs_render(states[i])) todo.push_back(i);
  // Earlier arrays Slurm still has, oldest first: the merge waits for them too.
  std::vector<std::string> old_arrays;
  for (const std::string& id : p.job_ids)
    if (queue.live_jobs.count(id)) old_arrays.push_back(id);
  std::error_code ec;
  if (todo.empty() && (queue.merge_queued || fs::exists(p.output, ec))) {
    std::fprintf(stderr, "glint farm: nothing to resubmit (every part is done, queued or running, and the merge %s)\n",
                 queue.merge_queued ? "is queued" : "is written");
    return 0;
  }
  if (o.dry_run) {
    if (queue.merge_queued) std::printf("%s\n", shell_words({"scancel", p.merge_job}).c_str());
    print_dry_run(p, dir, todo, false, old_arrays);
    return 0;
  }
  if (old_arrays.size() + split_array(todo, kMaxArrayChars).size() > kMaxFarmJobs)
    throw std::runtime_error("more than " + std::to_string(kMaxFarmJobs) +
                             " arrays of this farm would be queued: wait for some to end");
  if (queue.merge_queued) {
    // The old merge job waits for an array that failed: it would never run (or would fail).
    const ProgramResult r = run_program({"scancel", p.merge_job});
    if (r.exit_code != 0)
      std::fprintf(stderr, "glint farm: scancel %s failed (exit %d): %s\n", p.merge_job.c_str(), r.exit_code,
                   r.output.c_str());
  }
  p.job_ids = old_arrays;  // the arrays that ended need no squeue any more
  p.merge_job.clear();
  write_farm(p, dir);
  submit_farm(p, dir, todo, old_arrays);
  return 0;
}

}  // namespace

int run_farm_command(int argc, char** argv) {
  Options o;
  if (int code = parse_command_line("glint farm", kUsage, argc, argv, parse, o); code >= 0) return code;
  try {
    return o.command == "status" ? farm_status(o) : farm_slurm(o);
  } catch (const UsageError& e) {  // --width/--height beyond the project's film limits
    std::fprintf(stderr, "glint farm: %s\n", e.message.c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint farm: %s\n", e.what());
    return 1;
  }
}

}  // namespace glint
