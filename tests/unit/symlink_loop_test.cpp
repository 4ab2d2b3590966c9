// A symbolic link loop where a file is read (a project, a texture, an image) is reported with
// the OS reason, "Too many levels of symbolic links", not as a missing file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "renderer/image.h"
#include "renderer/project_file.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

constexpr const char* kLoop = "Too many levels of symbolic links";

// NAME -> NAME.other -> NAME in `dir`.
fs::path make_loop(const test::TempDir& dir, const std::string& name) {
  fs::create_symlink(name + ".other", dir / name);
  fs::create_symlink(name, dir / (name + ".other"));
  return dir / name;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SymlinkLoop, ImageGivesTheReason) {
  test::TempDir dir;
  const fs::path image = make_loop(dir, "loop.png");
  for (const std::string& message :
       {error_of([&] { probe_image(image); }),
        error_of([&] { load_image(image, ColorEncoding::srgb); })}) {
    EXPECT_EQ(message.rfind(image.string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(kLoop), std::string::npos) << message;
    EXPECT_EQ(message.find("not found"), std::string::npos) << message;
  }
}

TEST(SymlinkLoop, TextureOfAProjectGivesTheReasonAndItsJsonPath) {
  test::TempDir dir;
  make_loop(dir, "loop.png");
  std::ofstream(dir / "scene.glint")
      << R"({"format": "glint-project", "version": 1,
             "textures": [{"name": "wood", "path": "loop.png"}]})";
  const std::string message = error_of([&] { load_project(dir / "scene.glint"); });
  EXPECT_NE(message.find("textures[0].path"), std::string::npos) << message;
  EXPECT_NE(message.find(kLoop), std::string::npos) << message;
  EXPECT_EQ(message.find("not found"), std::string::npos) << message;
}

TEST(SymlinkLoop, ProjectGivesTheReason) {
  test::TempDir dir;
  const fs::path project = make_loop(dir, "loop.glint");
  const std::string message = error_of([&] { load_project(project); });
  EXPECT_EQ(message.rfind(project.string() + ": ", 0), 0u) << message;
  EXPECT_NE(message.find(kLoop), std::string::npos) << message;
}

}  // namespace
}  // namespace glint
