#include "app/run_program.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

extern char** environ;

namespace glint {
namespace {

// Closes a descriptor once, also on the error paths.
struct Fd {
  int fd = -1;
  ~Fd() { reset(); }
  void reset() {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
};

struct SpawnActions {
  posix_spawn_file_actions_t actions;
  SpawnActions() { posix_spawn_file_actions_init(&actions); }
  ~SpawnActions() { posix_spawn_file_actions_destroy(&actions); }
};

}  // namespace

ProgramResult run_program(const std::vector<std::string>& argv, size_t max_output) {
  if (argv.empty() || argv[0].empty()) throw ProgramError("run_program: no program given");
  for (const std::string& a : argv)
    if (a.find('\0') != std::string::npos) throw ProgramError(argv[0] + ": an argument holds a NUL byte");
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);

  int ends[2];
  if (::pipe2(ends, O_CLOEXEC) != 0) throw ProgramError(argv[0] + ": cannot make a pipe: " + std::strerror(errno));
  Fd read_end{ends[0]}, write_end{ends[1]};
  SpawnActions spawn;
  // dup2 clears close-on-exec on the copies: the child keeps only 0, 1 and 2 of these.
  posix_spawn_file_actions_addopen(&spawn.actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&spawn.actions, write_end.fd, 1);
  posix_spawn_file_actions_adddup2(&spawn.actions, write_end.fd, 2);
  pid_t pid = -1;
  const int error = ::posix_spawnp(&pid, argv[0].c_str(), &spawn.actions, nullptr, args.data(), environ);
  write_end.reset();  // the child's copies hold the pipe open; EOF comes when it exits
  if (error != 0) {
    ProgramError e(argv[0] + ": cannot run it: " + std::strerror(error) +
                   (error == ENOENT ? " (not on PATH)" : ""));
    e.not_found = error == ENOENT;
    throw e;
  }

  ProgramResult result;
  char buffer[65536];
  for (;;) {
    const ssize_t n = ::read(read_end.fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // EOF, or a read error: the exit status below still says how it ended
    const size_t room = max_output - std::min(max_output, result.output.size());
    result.output.append(buffer, std::min(room, static_cast<size_t>(n)));
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw ProgramError(argv[0] + ": cannot wait for it: " + std::strerror(errno));
  }
  if (WIFSIGNALED(status)) {
    result.signaled = true;
    result.exit_code = 128 + WTERMSIG(status);
  } else {
    result.exit_code = WEXITSTATUS(status);
  }
  return result;
}

std::string shell_words(const std::vector<std::string>& argv) {
  std::string line;
  for (const std::string& a : argv) {
    if (!line.empty()) line += ' ';
    const bool plain = !a.empty() && a.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                         "0123456789_-+=/.,:%@") == std::string::npos;
    if (plain) {
      line += a;
      continue;
    }
    line += '\'';
    for (char c : a) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += '\'';
  }
  return line;
}

}  // namespace glint
