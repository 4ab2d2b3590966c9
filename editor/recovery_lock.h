// The lock that tells a running editor's recovery files from a crashed one's. Each editor
// session autosaves under a name of its own and holds an exclusive flock(2) on that name's lock
// file while it runs; the kernel drops the lock when the process ends, however it ends. A
// recovery whose lock can be taken was therefore left by a session that is gone, and whoever
// takes the lock owns those files until it lets go: no two editors offer, recover or delete the
// same recovery at once.
//
// Both ways of taking a lock check, once it is held, that the lock file is still the one at
// its path: a session that deletes its files unlinks the lock file while holding it, and a
// process that opened that file just before cannot then mistake its lock for a valid one.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace glint {

class RecoveryLock {
 public:
  // The outcome of try_claim.
  enum class Claim { taken, held_elsewhere, gone, refused };

  // A lock file new in `dir` (created, never an existing one or through a link), locked: its
  // path is `dir`/PREFIX + 16 random hex digits + ".lock". Throws std::runtime_error
  // ("FILE: problem") where it cannot be created (no such folder, no permission, a full disk).
  static RecoveryLock create_unique(const std::filesystem::path& dir, const std::string& prefix);

  // Takes the lock of `lock_file`, creating the file when it is missing (the lock of an older
  // editor's recovery, or one removed by a cleaner). held_elsewhere: a live session holds it;
  // gone: the file was deleted meanwhile; refused: the path is a link or not a regular file, or
  // cannot be opened (`problem` says which).
  static Claim try_claim(const std::filesystem::path& lock_file, std::optional<RecoveryLock>& lock,
                         std::string& problem);

  RecoveryLock(RecoveryLock&& other) noexcept;
  RecoveryLock& operator=(RecoveryLock&& other) noexcept;
  RecoveryLock(const RecoveryLock&) = delete;
  RecoveryLock& operator=(const RecoveryLock&) = delete;
  ~RecoveryLock();  // lets go of the lock; the file stays

  const std::filesystem::path& path() const { return path_; }
  // Deletes the lock file, then lets go of the lock.
  void remove_and_release();

 private:
  RecoveryLock(int fd, std::filesystem::path path) : fd_(fd), path_(std::move(path)) {}
  void release();
  int fd_ = -1;
  std::filesystem::path path_;
};

}  // namespace glint
