#include "editor/recovery_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <random>
#include <stdexcept>
#include <utility>

namespace glint {
namespace fs = std::filesystem;
namespace {

// Whether `path` still names the file open as `fd` (not deleted, nor replaced by another).
bool still_at_path(int fd, const fs::path& path) {
  struct stat open_file {}, at_path {};
  return ::fstat(fd, &open_file) == 0 && ::lstat(path.c_str(), &at_path) == 0 &&
         open_file.st_dev == at_path.st_dev && open_file.st_ino == at_path.st_ino;
}

// Read-only is enough for flock, and lets a lock file that is not writable (or a read-only
// folder's existing one) still be locked.
constexpr int kOpenFlags = O_RDONLY | O_CREAT | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK | O_NOCTTY;

}  // namespace

RecoveryLock RecoveryLock::create_unique(const fs::path& dir, const std::string& prefix) {
  std::random_device random;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const uint64_t bits = uint64_t(random()) << 32 | random();
    char id[17];
    std::snprintf(id, sizeof id, "%016" PRIx64, bits);
    const fs::path path = dir / (prefix + id + ".lock");
    const int fd = ::open(path.c_str(), kOpenFlags | O_EXCL, 0600);
    if (fd < 0 && errno == EEXIST) continue;
    if (fd < 0)
      throw std::runtime_error(path.string() + ": cannot create the recovery lock file: " + std::strerror(errno));
    // Another editor's start-up may take a lock file that has no recovery yet for a stale one
    // and delete it: then this name is given up for another.
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0 && still_at_path(fd, path)) return RecoveryLock(fd, path);
    ::close(fd);
  }
  throw std::runtime_error((dir / prefix).string() + "*.lock: cannot create a recovery lock file of a new name");
}

RecoveryLock::Claim RecoveryLock::try_claim(const fs::path& lock_file, std::optional<RecoveryLock>& lock,
                                            std::string& problem) {
  lock.reset();
  problem.clear();
  const int fd = ::open(lock_file.c_str(), kOpenFlags, 0600);
  if (fd < 0) {
    problem = errno == ELOOP ? "is a symbolic link, not a lock file" : std::string("cannot open: ") + std::strerror(errno);
    return Claim::refused;
  }
  RecoveryLock held(fd, lock_file);  // closes it on every return below but the last
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    problem = "is not a regular file, not a lock file";
    return Claim::refused;
  }
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    if (errno == EWOULDBLOCK) return Claim::held_elsewhere;
    problem = std::string("cannot lock: ") + std::strerror(errno);
    return Claim::refused;
  }
  if (!still_at_path(fd, lock_file)) return Claim::gone;
  lock.emplace(std::move(held));
  return Claim::taken;
}

RecoveryLock::RecoveryLock(RecoveryLock&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), path_(std::move(other.path_)) {}

RecoveryLock& RecoveryLock::operator=(RecoveryLock&& other) noexcept {
  if (this != &other) {
    release();
    fd_ = std::exchange(other.fd_, -1);
    path_ = std::move(other.path_);
  }
  return *this;
}

RecoveryLock::~RecoveryLock() { release(); }

void RecoveryLock::release() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void RecoveryLock::remove_and_release() {
  if (fd_ >= 0) ::unlink(path_.c_str());
  release();
}

}  // namespace glint
