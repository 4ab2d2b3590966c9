// The plan of a `glint farm` render (OUT.farm/farm.json): what it renders, where, and the Slurm
// jobs submitted for it. The file is read as untrusted input: every field's type and range is
// checked, and every string that goes into a script or a command line holds no newline or NUL.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/render_part.h"

namespace glint {

constexpr int kMaxFarmParts = 100000;
// Array jobs a plan records (one per submission; a resume keeps only those Slurm still has).
constexpr size_t kMaxFarmJobs = 1000;
constexpr int kMaxGpusPerTask = 64;

struct FarmPlan {
  std::string project, output, glint;  // absolute paths
  int64_t spp = 0;
  int parts = 0;
  std::optional<long> width, height;
  std::string partition;  // empty: the cluster's default
  int gpus_per_task = 0;
  std::vector<std::string> job_ids;  // the part arrays submitted, oldest first
  std::string merge_job;             // empty: none submitted
};

// A farm.json that is not a plan: what() reads "FILE: FIELD: problem".
struct FarmPlanError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// OUT.farm beside OUT.
std::filesystem::path farm_folder(const std::string& output);
std::filesystem::path farm_plan_file(const std::filesystem::path& folder);
// Part i of K: the samples floor(i*N/K) .. floor((i+1)*N/K)-1.
SampleRange farm_part_range(const FarmPlan& plan, int i);
std::filesystem::path farm_part_file(const std::filesystem::path& folder, int i);

// Why `text` cannot go into a shell script or a Slurm directive (a newline or a NUL); nullopt
// when it can.
std::optional<std::string> script_text_problem(const std::string& text);
// Why `folder` cannot be a farm folder: a newline or NUL, or a backslash (sbatch's log file
// names: slurm_filename_literal).
std::optional<std::string> farm_folder_problem(const std::filesystem::path& folder);

std::string farm_plan_json(const FarmPlan& plan);
// The plan in `folder`; nullopt where it has no farm.json. Throws FarmPlanError for a file that
// is not a plan (naming the file and the field), StateFileError for one that cannot be read
// (a FIFO, a folder, over 1 MiB).
std::optional<FarmPlan> read_farm_plan(const std::filesystem::path& folder);

}  // namespace glint
