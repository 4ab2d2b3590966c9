#include "renderer/state_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "renderer/atomic_file.h"

namespace glint {

namespace fs = std::filesystem;

StateFileError::StateFileError(const fs::path& file, std::string problem_)
    : std::runtime_error(file.string() + ": " + problem_), problem(std::move(problem_)) {}

namespace {

std::string too_large(size_t size, size_t max_bytes) {
  return "is too large for a Glint state file (" + std::to_string(size) + " bytes, the limit is " +
         std::to_string(max_bytes) + ")";
}

struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::optional<std::string> read_state_file(const fs::path& file, size_t max_bytes) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer; the type is checked on the open file.
  Descriptor d{::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
  if (d.fd < 0) {
    if (errno == ENOENT) return std::nullopt;
    throw StateFileError(file, std::string("cannot open: ") + std::strerror(errno));
  }
  struct stat st {};
  if (::fstat(d.fd, &st) != 0) throw StateFileError(file, std::string("cannot read: ") + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw StateFileError(file, "is " + non_regular_kind(st.st_mode) + ", not a regular file");
  if (static_cast<uintmax_t>(st.st_size) > max_bytes) throw StateFileError(file, too_large(size_t(st.st_size), max_bytes));
  std::string text;
  text.reserve(static_cast<size_t>(st.st_size));
  char buffer[65536];
  for (;;) {  // at most one buffer past the limit: the file may grow after fstat
    const ssize_t n = ::read(d.fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw StateFileError(file, std::string("cannot read: ") + std::strerror(errno));
    if (n == 0) break;
    text.append(buffer, static_cast<size_t>(n));
    if (text.size() > max_bytes) throw StateFileError(file, too_large(text.size(), max_bytes));
  }
  return text;
}

void write_state_file(const fs::path& file, const std::string& text) {
  write_state_file_atomically(file, text.data(), text.size());
}

}  // namespace glint
