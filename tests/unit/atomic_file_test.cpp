// Saving images and projects (write_file_atomically, atomic_file.h): a full or read-only file
// system keeps the old file and names the OS reason, symbolic links to regular files are
// written through with the target's mode kept, devices, FIFOs, sockets and folders are never
// replaced, concurrent saves of one file all succeed, and a name near the file system's limit
// still has room for its temporary file. Glint's own state files (state_file.h) are never
// written through a link and are read only when regular and small.
#include <gtest/gtest.h>

#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "renderer/atomic_file.h"
#include "renderer/image.h"
#include "renderer/project_file.h"
#include "renderer/state_file.h"
#include "tests/small_tmpfs.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

#define REQUIRE_TMPFS(tmpfs) \
  if (!(tmpfs).mounted()) GTEST_SKIP() << (tmpfs).skip_reason()

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Pixels that no encoder compresses much: a w x h image takes at least w*h*3 bytes as PNG.
Image noise_image(int w, int h) {
  Image image;
  image.width = w;
  image.height = h;
  uint32_t state = 12345;
  for (int i = 0; i < w * h * 4; ++i) {
    state = state * 1664525u + 1013904223u;
    image.pixels.push_back(i % 4 == 3 ? 1.0f : float(state >> 8) / float(1 << 24));
  }
  return image;
}

Scene small_scene(const std::string& material_name = "white") {
  Scene s;
  s.materials.push_back({.name = material_name, .color = {1, 1, 1}});
  s.spheres.push_back({.name = "ball", .center = {0, 0, 0}, .radius = 1.0f, .material = material_name});
  return s;
}

mode_t mode_of(const fs::path& file) {
  struct stat st {};
  EXPECT_EQ(::stat(file.c_str(), &st), 0) << file;
  return st.st_mode & 07777;
}

// The image (256x256 of noise: 196 KiB as PNG, 256 KiB as HDR, 1 MiB as EXR) does not fit a
// 64 KiB tmpfs: the save fails with the OS reason, and the small file saved before stays byte
// for byte, with no temporary file left. (stb and tinyexr ignore write errors: without the
// checks the short file replaced the old one and the save "succeeded".)
TEST(AtomicFile, FullFileSystemKeepsTheOldImage) {
  test::SmallTmpfs tmpfs("64k");
  REQUIRE_TMPFS(tmpfs);
  for (const char* ext : {".png", ".hdr", ".exr"}) {
    const fs::path file = tmpfs / (std::string("out") + ext);
    save_image(file, noise_image(4, 4));
    const std::string old_bytes = read_bytes(file);
    ASSERT_FALSE(old_bytes.empty());
    try {
      save_image(file, noise_image(256, 256));
      ADD_FAILURE() << ext << ": a 256x256 image fit in 64 KiB";
    } catch (const ImageError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(file.string()), std::string::npos) << message;
      EXPECT_NE(message.find("No space left on device"), std::string::npos) << message;
      EXPECT_LT(message.size(), 300u) << message;
    }
    EXPECT_TRUE(read_bytes(file) == old_bytes) << ext;
    EXPECT_EQ(tmpfs.names(), std::vector<std::string>{file.filename().string()}) << ext;
    EXPECT_EQ(load_image(file, ColorEncoding::linear).width, 4) << ext;
    fs::remove(file);
  }
}

TEST(AtomicFile, FullFileSystemKeepsTheOldProject) {
  test::SmallTmpfs tmpfs("64k");
  REQUIRE_TMPFS(tmpfs);
  const fs::path file = tmpfs / "scene.glint";
  save_project(small_scene(), file);
  const std::string old_bytes = read_bytes(file);
  try {
    save_project(small_scene(std::string(100000, 'm')), file);
    ADD_FAILURE() << "a 100 KB project fit in 64 KiB";
  } catch (const ProjectError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(file.string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find("No space left on device"), std::string::npos) << message;
  }
  EXPECT_TRUE(read_bytes(file) == old_bytes);
  EXPECT_EQ(tmpfs.names(), std::vector<std::string>{"scene.glint"});
}

// A read-only mount: the reason is the OS's, both for the check before a render and the save.
TEST(AtomicFile, ReadOnlyFileSystemGivesTheReason) {
  test::SmallTmpfs tmpfs("64k");
  REQUIRE_TMPFS(tmpfs);
  const fs::path file = tmpfs / "out.png";
  save_image(file, noise_image(4, 4));
  const std::string old_bytes = read_bytes(file);
  const std::string remount = tmpfs.remount_read_only();
  if (!remount.empty()) GTEST_SKIP() << remount;
  const auto problem = file_write_problem(file);
  ASSERT_TRUE(problem.has_value());
  EXPECT_NE(problem->find("Read-only file system"), std::string::npos) << *problem;
  EXPECT_NE(problem->find(tmpfs.path().string()), std::string::npos) << *problem;
  try {
    save_image(file, noise_image(4, 4));
    ADD_FAILURE() << "saved on a read-only file system";
  } catch (const ImageError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(file.string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find("Read-only file system"), std::string::npos) << message;
  }
  EXPECT_THROW(save_project(small_scene(), tmpfs / "scene.glint"), ProjectError);
  EXPECT_TRUE(read_bytes(file) == old_bytes);
}

// Saving through a link updates the link's final target (in another folder, through a chain
// of relative and absolute links) and keeps the target's mode; the links stay links.
TEST(AtomicFile, SavesThroughSymbolicLinksAndKeepsTheMode) {
  test::TempDir dir;
  fs::create_directories(dir / "real");
  const fs::path target = dir / "real/out.png";
  save_image(target, noise_image(4, 4));
  ASSERT_EQ(::chmod(target.c_str(), 0640), 0);
  fs::create_symlink("real/out.png", dir / "link.png");   // relative
  fs::create_symlink(dir / "link.png", dir / "link2.png");  // absolute, to a link
  save_image(dir / "link2.png", noise_image(8, 2));
  EXPECT_TRUE(fs::is_symlink(dir / "link.png"));
  EXPECT_TRUE(fs::is_symlink(dir / "link2.png"));
  EXPECT_EQ(load_image(target, ColorEncoding::linear).width, 8);
  EXPECT_EQ(mode_of(target), 0640u);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "real"), fs::directory_iterator()), 1);

  // A project too, and a link whose target does not exist yet: the target is created.
  const fs::path project = dir / "real/scene.glint";
  save_project(small_scene(), project);
  ASSERT_EQ(::chmod(project.c_str(), 0600), 0);
  fs::create_symlink("real/scene.glint", dir / "scene.glint");
  save_project(small_scene("red"), dir / "scene.glint");
  EXPECT_TRUE(fs::is_symlink(dir / "scene.glint"));
  EXPECT_EQ(load_project(project).materials.at(0).name, "red");
  EXPECT_EQ(mode_of(project), 0600u);
  fs::create_symlink("real/new.exr", dir / "dangling.exr");
  save_image(dir / "dangling.exr", noise_image(2, 2));
  EXPECT_TRUE(fs::is_symlink(dir / "dangling.exr"));
  EXPECT_EQ(load_image(dir / "real/new.exr", ColorEncoding::linear).width, 2);
}

// A new file gets 0666 minus the umask, as from any program (not mkstemp's 0600).
TEST(AtomicFile, NewFilesFollowTheUmask) {
  test::TempDir dir;
  const mode_t old_mask = ::umask(027);
  save_image(dir / "a.png", noise_image(2, 2));
  save_project(small_scene(), dir / "a.glint");
  ::umask(002);
  save_image(dir / "b.png", noise_image(2, 2));
  ::umask(old_mask);
  EXPECT_EQ(mode_of(dir / "a.png"), 0640u);
  EXPECT_EQ(mode_of(dir / "a.glint"), 0640u);
  EXPECT_EQ(mode_of(dir / "b.png"), 0664u);
}

// Each save has its own temporary file: 50 saves of one file at once all succeed, and the
// file is one of them, whole. (A fixed FILE.tmp made some saves rename another's file or
// find theirs gone.)
TEST(AtomicFile, ConcurrentSavesOfOneFileAllSucceed) {
  test::TempDir dir;
  constexpr int kSaves = 50;
  std::atomic<int> failures{0};
  std::string first_error;
  std::vector<std::thread> threads;
  for (int i = 0; i < kSaves; ++i)
    threads.emplace_back([&, i] {
      try {
        if (i % 2) save_image(dir / "out.png", noise_image(16, 1 + i % 4));
        else save_project(small_scene("m" + std::to_string(i)), dir / "scene.glint");
      } catch (const std::exception& e) {
        if (failures++ == 0) first_error = e.what();
      }
    });
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(failures.load(), 0) << first_error;
  EXPECT_EQ(load_image(dir / "out.png", ColorEncoding::linear).width, 16);
  EXPECT_EQ(load_project(dir / "scene.glint").materials.size(), 1u);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 2);
}

// A 250-byte name is within NAME_MAX (255), so it saves: the temporary name has a fixed short
// length rather than the name plus a suffix. A 256-byte name is refused by the check before
// a render, with the reason.
TEST(AtomicFile, LongNamesLeaveRoomForTheTemporaryFile) {
  test::TempDir dir;
  const fs::path image = dir / (std::string(246, 'i') + ".png");
  const fs::path project = dir / (std::string(244, 'p') + ".glint");
  ASSERT_EQ(image.filename().string().size(), 250u);
  EXPECT_EQ(file_write_problem(image), std::nullopt);
  save_image(image, noise_image(2, 2));
  save_project(small_scene(), project);
  EXPECT_TRUE(fs::exists(image));
  EXPECT_TRUE(fs::exists(project));
  const fs::path too_long = dir / (std::string(252, 'x') + ".png");
  const auto problem = file_write_problem(too_long);
  ASSERT_TRUE(problem.has_value());
  EXPECT_NE(problem->find("File name too long"), std::string::npos) << *problem;
  EXPECT_THROW(save_image(too_long, noise_image(2, 2)), ImageError);
}

TEST(AtomicFile, WriteProblemsNameTheReason) {
  test::TempDir dir;
  EXPECT_EQ(file_write_problem(dir / "out.png"), std::nullopt);
  EXPECT_EQ(file_write_problem(dir / "missing/out.png"),
            "the folder " + (dir / "missing").string() + " does not exist");
  fs::create_directories(dir / "folder.png");
  EXPECT_EQ(file_write_problem(dir / "folder.png"), "is a folder");
  EXPECT_THROW(save_image(dir / "folder.png", noise_image(2, 2)), ImageError);
  fs::create_symlink("loop2.png", dir / "loop1.png");
  fs::create_symlink("loop1.png", dir / "loop2.png");
  EXPECT_EQ(file_write_problem(dir / "loop1.png"), "Too many levels of symbolic links");
  try {
    save_image(dir / "loop1.png", noise_image(2, 2));
    ADD_FAILURE() << "saved through a link loop";
  } catch (const ImageError& e) {
    EXPECT_NE(std::string(e.what()).find("Too many levels of symbolic links"), std::string::npos) << e.what();
  }
  // Nothing was left behind by the checks or the failed saves: folder.png and the two links.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 3);
}

// The kinds of file that no write may replace, made in the test's folder: a FIFO, a socket, a
// folder and, for root, a character device node (the numbers of /dev/null: harmless if written).
struct SpecialFiles {
  explicit SpecialFiles(const fs::path& dir) {
    fs::create_directories(dir / "folder");
    kinds.push_back({dir / "folder", "a folder"});
    EXPECT_EQ(::mkfifo((dir / "fifo").c_str(), 0600), 0);
    kinds.push_back({dir / "fifo", "a FIFO"});
    socket_fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    const std::string name = (dir / "socket").string();
    if (name.size() < sizeof address.sun_path) {
      std::copy(name.begin(), name.end(), address.sun_path);
      if (::bind(socket_fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0)
        kinds.push_back({dir / "socket", "a socket"});
    }
    if (::geteuid() == 0 && ::mknod((dir / "device").c_str(), S_IFCHR | 0600, makedev(1, 3)) == 0)
      kinds.push_back({dir / "device", "a character device"});
  }
  ~SpecialFiles() { ::close(socket_fd); }
  std::vector<std::pair<fs::path, std::string>> kinds;  // path, what the refusal calls it
  int socket_fd = -1;
};

bool still_special(const fs::path& file) {
  struct stat st {};
  return ::lstat(file.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
}

// A user-named output (an image, a project) that is, or links to, a device, FIFO, socket or
// folder is refused, naming what is there; the special file stays as it was and no temporary
// file is left. (The writer used to rename a regular file over them.)
TEST(AtomicFile, NeverReplacesADeviceFifoSocketOrFolder) {
  test::TempDir dir;
  SpecialFiles special(dir.path());
  ASSERT_GE(special.kinds.size(), 3u);
  for (const auto& [file, kind] : special.kinds) {
    const fs::path link = dir / ("link-to-" + file.filename().string() + ".png");
    fs::create_symlink(file, link);
    for (const fs::path& named : {file, link}) {
      const auto problem = file_write_problem(named);
      ASSERT_TRUE(problem.has_value()) << named;
      EXPECT_NE(problem->find(kind), std::string::npos) << *problem;
      try {
        write_file_atomically(named, "data", 4);
        ADD_FAILURE() << "wrote over " << kind << " through " << named;
      } catch (const FileWriteError& e) {
        EXPECT_NE(std::string(e.what()).find(named.string()), std::string::npos) << e.what();
        EXPECT_NE(e.problem.find(kind), std::string::npos) << e.problem;
      }
      EXPECT_THROW(save_image(named, noise_image(2, 2)), ImageError);
      EXPECT_THROW(save_project(small_scene(), named), ProjectError);
      EXPECT_TRUE(still_special(file)) << file << " was replaced";
    }
  }
  for (const auto& entry : fs::directory_iterator(dir.path()))
    EXPECT_NE(entry.path().filename().string().rfind(".glint-", 0), 0u) << "temporary file left: " << entry.path();
}

// Glint's own files (caches, editor state, farm plans) are never written through a link: a
// link planted at such a path, whatever it points to, is refused and its target keeps its
// contents; so is any other non-regular file. A regular file is replaced as usual.
TEST(AtomicFile, StateFilesAreNeverWrittenThroughALink) {
  test::TempDir dir;
  const fs::path precious = dir / "precious.txt";
  std::ofstream(precious) << "not Glint's";
  const fs::path state = dir / "backend.json";
  fs::create_symlink(precious, state);
  try {
    write_state_file(state, "{}");
    ADD_FAILURE() << "wrote through a link";
  } catch (const FileWriteError& e) {
    EXPECT_NE(std::string(e.what()).find(state.string()), std::string::npos) << e.what();
    EXPECT_NE(e.problem.find("symbolic link"), std::string::npos) << e.problem;
  }
  EXPECT_TRUE(fs::is_symlink(state));
  EXPECT_EQ(read_bytes(precious), "not Glint's");
  const fs::path dangling = dir / "layout.ini";  // a link to a file that does not exist yet
  fs::create_symlink(dir / "created-elsewhere", dangling);
  EXPECT_THROW(write_state_file(dangling, "x"), FileWriteError);
  EXPECT_FALSE(fs::exists(dir / "created-elsewhere"));

  SpecialFiles special(dir.path());
  for (const auto& [file, kind] : special.kinds) {
    EXPECT_THROW(write_state_file(file, "x"), FileWriteError) << kind;
    EXPECT_TRUE(still_special(file)) << file << " was replaced";
  }
  write_state_file(dir / "settings.json", "{\"a\": 1}");
  write_state_file(dir / "settings.json", "{}");
  EXPECT_EQ(read_bytes(dir / "settings.json"), "{}");
}

// Reading a state file never blocks or runs away: a FIFO (no writer) is refused at once, as are
// a folder, a device and a file over the cap (sparse, so it costs no disk); an absent file is
// nullopt. Each refusal names the file and what is there.
TEST(StateFile, ReadsOnlyRegularFilesWithinTheCap) {
  test::TempDir dir;
  EXPECT_EQ(read_state_file(dir / "absent.json"), std::nullopt);
  std::ofstream(dir / "small.json") << "{\"ok\": true}";
  EXPECT_EQ(read_state_file(dir / "small.json"), "{\"ok\": true}");
  SpecialFiles special(dir.path());
  for (const auto& [file, kind] : special.kinds) {
    if (kind == "a socket") continue;  // open(2) cannot open a socket: refused with the OS reason
    try {
      read_state_file(file);
      ADD_FAILURE() << "read " << kind;
    } catch (const StateFileError& e) {
      EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
      EXPECT_NE(e.problem.find(kind), std::string::npos) << e.problem;
    }
  }
  EXPECT_THROW(read_state_file(dir / "socket"), StateFileError);
  const fs::path huge = dir / "huge.json";
  std::ofstream(huge) << "";
  fs::resize_file(huge, uintmax_t(1) << 30);
  try {
    read_state_file(huge);
    ADD_FAILURE() << "read a 1 GiB state file";
  } catch (const StateFileError& e) {
    EXPECT_NE(e.problem.find("too large"), std::string::npos) << e.problem;
  }
  EXPECT_THROW(read_state_file(dir / "small.json", 4), StateFileError);
}

}  // namespace
}  // namespace glint
