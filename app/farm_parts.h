// The state of each part of a farm render: its file checked against the part the plan renders
// from the project as it is now (as `glint merge` checks parts against each other), and the
// array tasks Slurm still has (one `squeue` for all the plan's jobs).
#pragma once

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "app/farm_plan.h"
#include "renderer/render_part.h"

namespace glint {

enum class PartState {
  done,     // its file is the part the plan renders now
  queued,   // Slurm has its task, not started
  running,  // Slurm runs its task
  missing,  // no file, no task
  invalid,  // a file that is not a part of this range (and no task)
  stale,    // a part of the project as it was: the scene, an asset or the size changed (and no task)
};
const char* part_state_name(PartState state);
// Missing, invalid and stale parts are the ones --resume submits again.
bool needs_render(PartState state);

// The part headers each part file must have: loads the project as it is now. Throws for a
// project that cannot be loaded (naming it), or whose film no longer gives the plan's size.
std::vector<PartInfo> expected_parts(const FarmPlan& plan);

// Why a part's header is not `expected` (naming the file and the field that differs); nullopt
// when it is the part.
std::optional<std::string> part_difference(const std::filesystem::path& file, const PartInfo& expected,
                                           const PartInfo& found);

// What Slurm has of the plan's jobs.
struct QueueState {
  bool known = true;     // false: squeue could not say (see problem)
  std::string problem;   // why not
  std::vector<std::optional<PartState>> tasks;  // by part: queued or running, or nullopt
  std::set<std::string> live_jobs;  // the plan's arrays with a task still queued or running
  bool merge_queued = false;        // the plan's merge job is still queued or running
};
// Runs `squeue -h -r -j IDS -o '%i %T'` once for the plan's jobs (none when it has none).
QueueState query_queue(const FarmPlan& plan);

// Each part's state (from its file and the queue), with a note naming the file and the problem
// for each invalid or stale one.
std::vector<PartState> part_states(const FarmPlan& plan, const std::filesystem::path& folder,
                                   const QueueState& queue, const std::vector<PartInfo>& expected,
                                   std::vector<std::string>& notes);

}  // namespace glint
