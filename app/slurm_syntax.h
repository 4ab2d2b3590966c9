// What `glint farm` writes for Slurm and reads back from it, checked and spelled one way: job
// ids, partition names, array index lists, log file names (sbatch's filename patterns) and the
// lines of `squeue -h -r -o '%i %T'`.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace glint {

// Why `text` is not a Slurm job id as sbatch --parsable prints it (decimal digits, 1 to
// 4294967295); nullopt when it is one.
std::optional<std::string> job_id_problem(const std::string& text);

// Why `text` is not a partition glint farm passes to sbatch --partition: one or more names
// separated by commas, each of letters, digits, '_', '-' and '.', not starting with '-', at most
// 64 characters in all; nullopt when it is one.
std::optional<std::string> partition_problem(const std::string& text);

// Sorted, distinct array indices as sbatch --array takes them, runs as ranges: "0-29999",
// "3,7-9". Empty for no indices.
std::string array_ranges(const std::vector<int>& sorted_indices);

// The same indices in groups whose array_ranges are at most `max_chars` long (a resubmission of
// scattered parts could exceed what one argument may hold), each group sorted.
std::vector<std::vector<int>> split_array(const std::vector<int>& sorted_indices, size_t max_chars);

// sbatch --dependency for a job that runs once every job of `afterok` succeeded and every job
// of `afterany` ended: "afterok:A:B,afterany:C"; empty for none.
std::string dependency_list(const std::vector<std::string>& afterok, const std::vector<std::string>& afterany);

// `path` as sbatch --output takes it literally: '%' doubled (sbatch's filename patterns replace
// %j, %a, %A, ...). Nullopt for a path with a backslash: one anywhere turns off every pattern and
// is dropped (Slurm's fname.c), so a path with one cannot be given together with %a.
std::optional<std::string> slurm_filename_literal(const std::string& path);

// One task of an array that Slurm still has, from a line "JOB_TASK STATE" of
// `squeue -h -r -o '%i %T'`, or a plain job "JOB STATE" (task -1).
struct QueuedJob {
  std::string job;
  int task = -1;
  std::string state;
};
// The lines of squeue's output that are well-formed; others (warnings) are skipped.
std::vector<QueuedJob> parse_squeue_lines(const std::string& output);

}  // namespace glint
