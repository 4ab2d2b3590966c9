#include "renderer/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdint>
#include <cstring>
#include <random>
#include <system_error>

namespace glint {

namespace fs = std::filesystem;

namespace {

std::string os_error(int error) { return std::strerror(error); }

// The folder a file is created in: "" (a bare file name) is the current folder.
fs::path folder_of(const fs::path& file) {
  const fs::path dir = file.parent_path();
  return dir.empty() ? fs::path(".") : dir;
}

// Creates a new file of a unique name in `dir` for writing, like mkstemp, but with the mode
// 0666 passed to open so that the kernel applies the umask (and a default ACL) as for any new
// file; mkstemp's 0600 would leave the saved file private. Returns the descriptor, or -1 with
// errno set.
int create_temporary(const fs::path& dir, fs::path& tmp) {
  static constexpr char kAlphabet[] =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  std::random_device random;
  for (int attempt = 0; attempt < 100; ++attempt) {
    uint64_t bits = uint64_t(random()) << 32 | random();
    std::string name = ".glint-";
    for (int i = 0; i < 8; ++i, bits /= 62) name += kAlphabet[bits % 62];
    name += ".tmp";
    tmp = dir / name;
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  errno = EEXIST;
  return -1;
}

// Writes all of `data` to `fd`; returns "" or the problem.
std::string write_all(int fd, const unsigned char* data, size_t size) {
  for (size_t done = 0; done < size;) {
    const ssize_t n = ::write(fd, data + done, size - done);
    if (n > 0) done += static_cast<size_t>(n);
    else if (n < 0 && errno == EINTR) continue;
    else return "cannot write: " + os_error(n < 0 ? errno : EIO);
  }
  return "";
}

// Why `target` (the end of the link chain from `file`) must not be replaced, or "": it exists
// and is not a regular file.
std::string target_problem(const fs::path& file, const fs::path& target) {
  struct stat st {};
  if (::lstat(target.c_str(), &st) != 0) return "";
  const std::string kind = non_regular_kind(st.st_mode);
  if (kind.empty()) return "";
  if (S_ISDIR(st.st_mode) && target == file) return "is a folder";
  if (target == file) return "is " + kind + ", not a regular file: not written";
  return "is a symbolic link to " + target.string() + ", which is " + kind + ", not a regular file: not written";
}

void replace_file(const fs::path& file, const fs::path& target, const void* data, size_t size);

}  // namespace

std::string non_regular_kind(unsigned mode) {
  if (S_ISREG(mode)) return "";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

FileWriteError::FileWriteError(const fs::path& file, std::string problem_)
    : std::runtime_error(file.string() + ": " + problem_), problem(std::move(problem_)) {}

fs::path write_target(const fs::path& file) {
  // Linux follows at most 40 links in one path (MAXSYMLINKS); so do we.
  constexpr int kMaxLinks = 40;
  fs::path path = file;
  for (int links = 0;; ++links) {
    std::error_code ec;
    const fs::file_status status = fs::symlink_status(path, ec);
    if (ec || !fs::is_symlink(status)) return path;  // absent, or not a link: written itself
    if (links == kMaxLinks) throw FileWriteError(file, os_error(ELOOP));
    const fs::path link = fs::read_symlink(path, ec);
    if (ec) throw FileWriteError(file, "cannot read the symbolic link: " + ec.message());
    path = link.is_absolute() ? link : path.parent_path() / link;
  }
}

void write_file_atomically(const fs::path& file, const void* data, size_t size) {
  const fs::path target = write_target(file);
  if (const std::string problem = target_problem(file, target); !problem.empty()) throw FileWriteError(file, problem);
  replace_file(file, target, data, size);
}

void write_state_file_atomically(const fs::path& file, const void* data, size_t size) {
  struct stat st {};
  if (::lstat(file.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    const std::string kind = non_regular_kind(st.st_mode);
    throw FileWriteError(file, "is " + kind + "; Glint writes its own files only as regular files, never through "
                               "a link (remove it to let Glint write there)");
  }
  replace_file(file, file, data, size);
}

namespace {

// Writes a temporary file beside `target` and renames it over `target` (a regular file or
// none), keeping the old file's mode and owner. `file` names it in errors.
void replace_file(const fs::path& file, const fs::path& target, const void* data, size_t size) {
  const fs::path dir = folder_of(target);
  struct stat old {};
  const bool replacing = ::lstat(target.c_str(), &old) == 0;

  fs::path tmp;
  const int fd = create_temporary(dir, tmp);
  if (fd < 0)
    throw FileWriteError(file, "cannot create a file in " + dir.string() + ": " + os_error(errno));
  std::string error;
  if (replacing) {
    // The owner first: chown clears the set-user-ID and set-group-ID bits. Only root may give
    // a file away, so a failure here is expected for other users and is not an error.
    if (old.st_uid != ::geteuid() || old.st_gid != ::getegid()) {
      [[maybe_unused]] const int ignored = ::fchown(fd, old.st_uid, old.st_gid);
    }
    if (::fchmod(fd, old.st_mode & 07777) != 0)
      error = "cannot keep the file's permissions: " + os_error(errno);
  }
  if (error.empty()) error = write_all(fd, static_cast<const unsigned char*>(data), size);
  if (error.empty() && ::fsync(fd) != 0) error = "cannot write (fsync): " + os_error(errno);
  if (::close(fd) != 0 && error.empty()) error = "cannot write (close): " + os_error(errno);
  // Checked again just before the rename: a FIFO or device put there during the write stays.
  if (error.empty()) {
    struct stat now {};
    if (::lstat(target.c_str(), &now) == 0 && !S_ISREG(now.st_mode))
      error = "became " + non_regular_kind(now.st_mode) + " while it was written: not replaced";
  }
  if (error.empty() && ::rename(tmp.c_str(), target.c_str()) != 0)
    error = "cannot replace the file: " + os_error(errno);
  if (!error.empty()) {
    ::unlink(tmp.c_str());
    throw FileWriteError(file, error);
  }
  // Make the rename itself durable (best effort: some file systems refuse to sync a folder).
  if (const int dir_fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dir_fd >= 0) {
    ::fsync(dir_fd);
    ::close(dir_fd);
  }
}

}  // namespace

std::optional<std::string> file_write_problem(const fs::path& file) {
  fs::path target;
  try {
    target = write_target(file);
  } catch (const FileWriteError& e) {
    return e.problem;
  }
  const fs::path dir = folder_of(target);
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0) {
    if (errno == ENOENT) return "the folder " + dir.string() + " does not exist";
    return "the folder " + dir.string() + ": " + os_error(errno);
  }
  if (!S_ISDIR(st.st_mode)) return dir.string() + " is not a folder";
  long name_max = ::pathconf(dir.c_str(), _PC_NAME_MAX);
  if (name_max <= 0) name_max = NAME_MAX;
  const size_t name_length = target.filename().native().size();
  if (name_length > static_cast<size_t>(name_max))
    return os_error(ENAMETOOLONG) + " (the name has " + std::to_string(name_length) +
           " bytes, this file system allows " + std::to_string(name_max) + ")";
  if (const std::string problem = target_problem(file, target); !problem.empty()) return problem;
  // Writability (permissions, a read-only mount, no space for a new file) is best known by
  // trying: the same call that write_file_atomically makes.
  fs::path tmp;
  const int fd = create_temporary(dir, tmp);
  if (fd < 0) return "cannot create a file in " + dir.string() + ": " + os_error(errno);
  ::close(fd);
  ::unlink(tmp.c_str());
  return std::nullopt;
}

}  // namespace glint
