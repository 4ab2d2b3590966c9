// A small tmpfs mounted on a fresh folder, for tests of full and read-only file systems (the
// unit and editor tests). Mounting needs root with CAP_SYS_ADMIN; where it is not permitted,
// mounted() is false and skip_reason() says why, for GTEST_SKIP.
#pragma once

#include <sys/mount.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "tests/temp_dir.h"

namespace glint::test {

class SmallTmpfs {
 public:
  // `size` as mount's option takes it ("64k").
  explicit SmallTmpfs(const std::string& size) {
    const std::string options = "size=" + size + ",mode=0755";
    if (::mount("tmpfs", dir_.path().c_str(), "tmpfs", 0, options.c_str()) == 0)
      mounted_ = true;
    else
      skip_reason_ = "cannot mount a tmpfs on " + dir_.path().string() + ": " +
                     std::strerror(errno) + " (needs root with CAP_SYS_ADMIN)";
  }
  ~SmallTmpfs() {
    if (mounted_) ::umount2(dir_.path().c_str(), MNT_DETACH);
  }
  SmallTmpfs(const SmallTmpfs&) = delete;
  SmallTmpfs& operator=(const SmallTmpfs&) = delete;

  bool mounted() const { return mounted_; }
  const std::string& skip_reason() const { return skip_reason_; }
  const std::filesystem::path& path() const { return dir_.path(); }
  std::filesystem::path operator/(const std::string& name) const { return dir_.path() / name; }

  // Makes the file system read-only; returns "" or the reason it failed.
  std::string remount_read_only() {
    if (::mount(nullptr, dir_.path().c_str(), nullptr, MS_REMOUNT | MS_RDONLY, nullptr) == 0) return "";
    return std::string("cannot remount read-only: ") + std::strerror(errno);
  }

  // Fills the remaining space with a file named `name`; returns the bytes written.
  size_t fill(const std::string& name = "filler") {
    const std::string file = (dir_.path() / name).string();
    FILE* f = std::fopen(file.c_str(), "wb");
    if (!f) return 0;
    std::setvbuf(f, nullptr, _IONBF, 0);
    const std::vector<char> block(512, 'x');
    size_t written = 0;
    for (size_t n; (n = std::fwrite(block.data(), 1, block.size(), f)) > 0;) written += n;
    std::fclose(f);
    return written;
  }

  // The names in the folder, sorted (to show that no temporary file was left).
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& entry : std::filesystem::directory_iterator(dir_.path()))
      out.push_back(entry.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
  }

 private:
  TempDir dir_;
  bool mounted_ = false;
  std::string skip_reason_;
};

}  // namespace glint::test
