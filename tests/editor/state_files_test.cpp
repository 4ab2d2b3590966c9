// The editor's own files as hostile input: a FIFO, a folder or a file over the size cap at the
// path of settings.json, layout.ini, recent.json or a recovery file must neither hang nor stop
// the editor (the defaults are used, with a note naming the file), and a symbolic link planted
// there must never be written through (the save is refused with a note, and the link's target
// keeps its contents). Every FIFO, link and big (sparse) file is made in the test's own folder.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <functional>
#include <future>
#include <sstream>
#include <vector>

#include <gtest/gtest.h>
#include <imgui.h>

#include "editor/recent_and_recovery.h"
#include "editor/scene_edits.h"
#include "editor/ui_layout.h"
#include "editor_test_util.h"
#include "renderer/project_file.h"
#include "renderer/state_file.h"

namespace glint {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

enum class Hostile { fifo, folder, huge };

const char* name_of(Hostile kind) {
  return kind == Hostile::fifo ? "a FIFO" : kind == Hostile::folder ? "a folder" : "too large";
}

void PrintTo(Hostile kind, std::ostream* out) { *out << name_of(kind); }

// Puts a FIFO, a folder or a sparse file one byte over `cap` at `file`.
void plant(Hostile kind, const fs::path& file, uintmax_t cap = kMaxStateFileBytes) {
  fs::create_directories(file.parent_path());
  switch (kind) {
    case Hostile::fifo: ASSERT_EQ(::mkfifo(file.c_str(), 0600), 0); break;
    case Hostile::folder: fs::create_directory(file); break;
    case Hostile::huge:
      std::ofstream(file).put('[');
      fs::resize_file(file, cap + 1);  // sparse: no disk space used
      break;
  }
}

// Runs `load` with a time limit. A FIFO must not block the reader: if one does, the FIFOs are
// opened for writing (again each time the reader blocks anew) to free it, and the test fails
// instead of hanging.
void within_seconds(const std::function<void()>& load, const std::vector<fs::path>& fifos = {}) {
  auto done = std::async(std::launch::async, load);
  if (done.wait_for(std::chrono::seconds(10)) == std::future_status::ready) return done.get();
  ADD_FAILURE() << "reading the state files blocked";
  while (done.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready)
    for (const fs::path& fifo : fifos)
      if (const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK); fd >= 0) ::close(fd);
}

std::string contents(const fs::path& file) {
  std::stringstream text;
  text << std::ifstream(file, std::ios::binary).rdbuf();
  return text.str();
}

// A link at `file` to a file of the test's folder holding `victim_text`; returns that file.
fs::path plant_link(const fs::path& file, const std::string& victim_text) {
  const fs::path victim = file.parent_path() / ("victim-of-" + file.filename().string());
  std::ofstream(victim) << victim_text;
  fs::create_directories(file.parent_path());
  fs::create_symlink(victim, file);
  return victim;
}

void expect_note(const std::string& note, const fs::path& file, const std::string& what) {
  EXPECT_NE(note.find(file.string()), std::string::npos) << note;
  EXPECT_NE(note.find(what), std::string::npos) << note;
}

class StateFiles : public ::testing::TestWithParam<Hostile> {};

TEST_P(StateFiles, RecentFilesFallBackToAnEmptyList) {
  TempDir dir;
  const fs::path file = dir / "recent.json";
  plant(GetParam(), file);
  within_seconds([&] {
    std::string note;
    EXPECT_TRUE(load_recent_files(note, dir.path()).empty());
    expect_note(note, file, name_of(GetParam()));
    EXPECT_NE(note.find("empty"), std::string::npos) << note;
    // Opening a project still works and names the file; what is there is not replaced.
    const auto list = add_recent_file("/p/a.glint", note, dir.path());
    EXPECT_EQ(list, std::vector<fs::path>{"/p/a.glint"});
    expect_note(note, file, "not updated");
    remove_recent_file("/p/a.glint", note, dir.path());
    expect_note(note, file, "not updated");
  }, {file});
  EXPECT_EQ(fs::symlink_status(file).type(), GetParam() == Hostile::fifo     ? fs::file_type::fifo
                                             : GetParam() == Hostile::folder ? fs::file_type::directory
                                                                             : fs::file_type::regular);
}

TEST_P(StateFiles, SettingsFallBackToTheDefaults) {
  TempDir dir;
  const fs::path file = dir / "settings.json";
  plant(GetParam(), file);
  within_seconds([&] {
    std::string note;
    EXPECT_EQ(load_editor_settings(note, dir.path()), EditorSettings{});
    expect_note(note, file, name_of(GetParam()));
    EXPECT_NE(note.find("default settings"), std::string::npos) << note;
  }, {file});
}

TEST_P(StateFiles, LayoutFallsBackToTheDefault) {
  TempDir dir;
  const fs::path file = layout_file_path(dir.path());
  plant(GetParam(), file);
  ImGui::CreateContext();
  within_seconds([&] {
    std::string error;
    load_layout(file, error);
    expect_note(error, file, name_of(GetParam()));
    EXPECT_NE(error.find("default layout"), std::string::npos) << error;
  }, {file});
  ImGui::DestroyContext();
}

// A recovery file that cannot be read is not offered, is noted and stays on disk; a sidecar
// that cannot be read is noted, and its recovery is still offered (based in the recovery folder).
TEST_P(StateFiles, RecoveryFilesAreNotedNotFatal) {
  TempDir dir;
  const fs::path file = dir / "recovery-00000000000000aa.glint";
  plant(GetParam(), file, kMaxProjectBytes);
  Document doc;
  add_sphere(doc.scene);
  fs::path sidecar;
  {
    Autosave crashed(dir.path(), 0);  // a session with a readable recovery but a bad sidecar
    ASSERT_TRUE(crashed.update(doc, 1));
    sidecar = fs::path(crashed.file()).replace_extension(".json");
    fs::remove(sidecar);
    plant(GetParam(), sidecar);
  }
  within_seconds([&] {
    std::vector<std::string> notes;
    const std::vector<Recovery> found = find_recoveries(notes, dir.path());
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].scene.spheres.size(), 2u);
    EXPECT_EQ(found[0].scene.base_dir, dir.path());
    ASSERT_EQ(notes.size(), 2u);
    for (const std::string& note : notes) EXPECT_NE(note.find(name_of(GetParam())), std::string::npos) << note;
    const bool first_is_file = notes[0].find(file.string()) != std::string::npos;
    expect_note(notes[first_is_file ? 0 : 1], file, "not offered");
    expect_note(notes[first_is_file ? 1 : 0], sidecar, "recovery folder");
  }, {file, sidecar});
  EXPECT_TRUE(fs::exists(file));
}

INSTANTIATE_TEST_SUITE_P(Hostile, StateFiles, ::testing::Values(Hostile::fifo, Hostile::folder, Hostile::huge),
                         [](const auto& info) {
                           return std::string(info.param == Hostile::fifo     ? "Fifo"
                                              : info.param == Hostile::folder ? "Folder"
                                                                              : "OverTheCap");
                         });

// ---- Links planted at the paths the editor writes: refused, noted, the target unchanged.

TEST(StateFileLinks, RecentFilesAreNotWrittenThroughALink) {
  TempDir dir;
  const fs::path victim = plant_link(dir / "recent.json", "{\"files\": [\"/p/kept.glint\"]}\n");
  std::string note;
  const auto list = add_recent_file("/p/a.glint", note, dir.path());
  expect_note(note, dir / "recent.json", "symbolic link");
  EXPECT_NE(note.find("not saved"), std::string::npos) << note;
  EXPECT_EQ(contents(victim), "{\"files\": [\"/p/kept.glint\"]}\n");
  EXPECT_TRUE(fs::is_symlink(dir / "recent.json"));
  EXPECT_EQ(list.front(), fs::path("/p/a.glint"));  // this session's list still has it
}

TEST(StateFileLinks, SettingsAreNotWrittenThroughALink) {
  TempDir dir;
  const fs::path victim = plant_link(dir / "settings.json", "precious");
  std::string note;
  EditorSettings s;
  s.preview = ViewportResolution::half;
  save_editor_settings(s, note, dir.path());
  expect_note(note, dir / "settings.json", "symbolic link");
  EXPECT_NE(note.find("not saved"), std::string::npos) << note;
  EXPECT_EQ(contents(victim), "precious");
  EXPECT_TRUE(fs::is_symlink(dir / "settings.json"));
}

TEST(StateFileLinks, LayoutIsNotWrittenThroughALink) {
  TempDir dir;
  const fs::path file = layout_file_path(dir.path());
  const fs::path victim = plant_link(file, "precious");
  ImGui::CreateContext();
  std::string error;
  EXPECT_FALSE(save_layout_if_needed(file, /*force=*/true, error));
  ImGui::DestroyContext();
  expect_note(error, file, "symbolic link");
  EXPECT_NE(error.find("not saved"), std::string::npos) << error;
  EXPECT_EQ(contents(victim), "precious");
  EXPECT_TRUE(fs::is_symlink(file));
}

// A link planted at a session's recovery file or sidecar once their name is known: the autosave
// fails (shown in the status line) and the target keeps its contents.
TEST(StateFileLinks, RecoveryFilesAreNotWrittenThroughALink) {
  for (const char* ext : {".glint", ".json"}) {
    TempDir dir;
    Autosave autosave(dir.path(), 0);
    Document doc;
    add_sphere(doc.scene);
    ASSERT_TRUE(autosave.update(doc, 1));
    const fs::path file = fs::path(autosave.file()).replace_extension(ext);
    fs::remove(file);
    const fs::path victim = plant_link(file, "precious");
    add_sphere(doc.scene);
    EXPECT_FALSE(autosave.update(doc, 2));
    expect_note(autosave.last_error(), file, "symbolic link");
    EXPECT_EQ(contents(victim), "precious") << ext;
    EXPECT_TRUE(fs::is_symlink(file));
  }
}

// A link planted at the lock file of a crashed session's recovery: the lock is not taken through
// it, the recovery is not offered, and the note says why.
TEST(StateFileLinks, ALinkAtALockFileIsRefused) {
  TempDir dir;
  Document doc;
  add_sphere(doc.scene);
  fs::path lock;
  {
    Autosave crashed(dir.path(), 0);
    ASSERT_TRUE(crashed.update(doc, 1));
    lock = fs::path(crashed.file()).replace_extension(".lock");
  }
  fs::remove(lock);
  const fs::path victim = plant_link(lock, "precious");
  std::vector<std::string> notes;
  EXPECT_TRUE(find_recoveries(notes, dir.path()).empty());
  ASSERT_EQ(notes.size(), 1u);
  expect_note(notes[0], lock, "symbolic link");
  EXPECT_EQ(contents(victim), "precious");
}

}  // namespace
}  // namespace glint
