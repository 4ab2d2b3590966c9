#include "app/farm_parts.h"

#include <cstdio>
#include <stdexcept>
#include <system_error>

#include "app/command_line.h"
#include "app/render_size.h"
#include "app/run_program.h"
#include "app/slurm_syntax.h"
#include "renderer/project_file.h"
#include "renderer/render_options.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

std::string hex(uint64_t v) {
  char s[20];
  std::snprintf(s, sizeof s, "%016llx", static_cast<unsigned long long>(v));
  return s;
}

std::string display_text(const DisplaySettings& d) {
  char s[64];
  std::snprintf(s, sizeof s, "exposure %.9g, tonemap %s", d.exposure, to_string(d.tonemap));
  return s;
}

// The first line of a program's output, for a one-line message.
std::string first_line(const std::string& text) {
  const std::string line = text.substr(0, text.find('\n'));
  return line.size() > 200 ? line.substr(0, 200) + "..." : line;
}

}  // namespace

const char* part_state_name(PartState s) {
  switch (s) {
    case PartState::done: return "done";
    case PartState::queued: return "queued";
    case PartState::running: return "running";
    case PartState::missing: return "missing";
    case PartState::invalid: return "invalid";
    case PartState::stale: return "stale";
  }
  return "?";
}

bool needs_render(PartState s) {
  return s == PartState::missing || s == PartState::invalid || s == PartState::stale;
}

std::vector<PartInfo> expected_parts(const FarmPlan& plan) {
  Scene scene;
  try {
    scene = load_project(plan.project);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("cannot check the parts against the project: ") + e.what());
  }
  std::pair<int, int> size;
  try {
    size = render_size(plan.width, plan.height, scene.film);
  } catch (const UsageError& e) {
    throw std::runtime_error(plan.project + ": the plan's " + e.message);
  }
  // As each part's task runs it: `glint render PROJECT --samples A:B [--width W] [--height H]`,
  // every estimator option at its default (the sample range is not in the digest).
  std::vector<PartInfo> parts;
  for (int i = 0; i < plan.parts; ++i)
    parts.push_back(part_info(scene, RenderOptions{}, size.first, size.second, farm_part_range(plan, i)));
  return parts;
}

std::optional<std::string> part_difference(const fs::path& file, const PartInfo& expected, const PartInfo& found) {
  std::string fields;
  auto differs = [&](const std::string& what, const std::string& was, const std::string& now) {
    fields += (fields.empty() ? "" : "; ") + ("its " + what + " is " + was + ", not " + now);
  };
  if (found.digest != expected.digest)
    differs("digest (scene, assets and estimator options)", hex(found.digest), hex(expected.digest));
  if (found.width != expected.width || found.height != expected.height)
    differs("size", std::to_string(found.width) + "x" + std::to_string(found.height),
            std::to_string(expected.width) + "x" + std::to_string(expected.height));
  if (found.seed != expected.seed) differs("seed", std::to_string(found.seed), std::to_string(expected.seed));
  if (found.sampler != expected.sampler)
    differs("sampler", found.sampler == SamplerKind::sobol ? "sobol" : "pcg",
            expected.sampler == SamplerKind::sobol ? "sobol" : "pcg");
  if (!(found.display == expected.display))
    differs("display settings", display_text(found.display), display_text(expected.display));
  if (fields.empty()) return std::nullopt;
  return file.string() + ": stale (" + fields + " as the project renders now)";
}

QueueState query_queue(const FarmPlan& plan) {
  QueueState q;
  q.tasks.assign(static_cast<size_t>(plan.parts), std::nullopt);
  std::string ids;
  for (const std::string& id : plan.job_ids) ids += (ids.empty() ? "" : ",") + id;
  if (!plan.merge_job.empty()) ids += (ids.empty() ? "" : ",") + plan.merge_job;
  if (ids.empty()) return q;
  ProgramResult r;
  try {
    r = run_program({"squeue", "-h", "-r", "-j", ids, "-o", "%i %T"});
  } catch (const ProgramError& e) {
    q.known = false;
    q.problem = e.what();
    return q;
  }
  if (r.exit_code != 0) {
    // With one id, squeue refuses an id that Slurm has forgotten: none of them is queued.
    if (r.output.find("Invalid job id") != std::string::npos) return q;
    q.known = false;
    q.problem = "squeue failed (exit " + std::to_string(r.exit_code) + "): " + first_line(r.output);
    return q;
  }
  const std::set<std::string> arrays(plan.job_ids.begin(), plan.job_ids.end());
  for (const QueuedJob& job : parse_squeue_lines(r.output)) {
    if (job.task < 0) {
      q.merge_queued = q.merge_queued || job.job == plan.merge_job;
      continue;
    }
    if (!arrays.count(job.job) || job.task >= plan.parts) continue;
    q.live_jobs.insert(job.job);
    const PartState state = job.state == "RUNNING" ? PartState::running : PartState::queued;
    auto& task = q.tasks[static_cast<size_t>(job.task)];
    if (!task || state == PartState::running) task = state;  // a task in two arrays: the running one
  }
  return q;
}

namespace {

// The state of part i's file: done, or invalid or stale with a note; nullopt where there is none.
std::optional<PartState> file_state(const fs::path& file, const PartInfo& expected, std::vector<std::string>& notes) {
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (!fs::exists(status) && !fs::is_symlink(fs::symlink_status(file, ec))) return std::nullopt;
  if (!fs::is_regular_file(status)) {  // reading a FIFO would block
    notes.push_back(file.string() + ": not a regular file");
    return PartState::invalid;
  }
  try {
    const PartInfo found = read_part_header(file);
    if (!(found.range == expected.range)) {
      notes.push_back(file.string() + ": samples " + format_sample_range(found.range) + ", not " +
                      format_sample_range(expected.range));
      return PartState::invalid;
    }
    if (const auto difference = part_difference(file, expected, found)) {
      notes.push_back(*difference);
      return PartState::stale;
    }
    return PartState::done;
  } catch (const std::exception& e) {
    notes.push_back(e.what());
    return PartState::invalid;
  }
}

}  // namespace

std::vector<PartState> part_states(const FarmPlan& plan, const fs::path& folder, const QueueState& queue,
                                   const std::vector<PartInfo>& expected, std::vector<std::string>& notes) {
  std::vector<PartState> states(static_cast<size_t>(plan.parts), PartState::missing);
  for (int i = 0; i < plan.parts; ++i) {
    const std::optional<PartState> file = file_state(farm_part_file(folder, i), expected[i], notes);
    if (file == PartState::done) states[i] = PartState::done;  // a rerun still queued changes nothing
    else if (queue.tasks[i]) states[i] = *queue.tasks[i];     // its task will write it
    else if (file) states[i] = *file;
  }
  return states;
}

}  // namespace glint
