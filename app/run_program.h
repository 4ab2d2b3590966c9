// Running another program (sbatch, squeue, scancel) with an argument vector: no shell ever
// reads a command line, so a path, a job id or a value from a file is one argument whatever it
// holds. The program is looked up on PATH, reads /dev/null, and its standard output and error
// come back together.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace glint {

struct ProgramResult {
  int exit_code = 0;   // the exit status, or 128 + the signal that ended it
  bool signaled = false;
  std::string output;  // stdout and stderr interleaved, at most the cap (the rest is read and dropped)
};

// The program could not be started (not on PATH, not executable): what() names it and why.
struct ProgramError : std::runtime_error {
  using std::runtime_error::runtime_error;
  bool not_found = false;  // no such program on PATH
};

constexpr size_t kMaxProgramOutput = size_t(4) << 20;

// Runs argv[0] (looked up on PATH) with the arguments argv[1..], waits for it and returns its
// exit status and output. Throws ProgramError when it cannot be started.
ProgramResult run_program(const std::vector<std::string>& argv, size_t max_output = kMaxProgramOutput);

// argv as a shell would need it typed (each argument single-quoted where it has to be), for
// messages and --dry-run: never run.
std::string shell_words(const std::vector<std::string>& argv);

}  // namespace glint
