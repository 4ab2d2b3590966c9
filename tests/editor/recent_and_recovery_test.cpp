// Recent files, settings and crash recovery, in a temporary folder instead of $HOME. The
// editor's state files as hostile input (FIFOs, folders, huge files, links) are in
// state_files_test.cpp.
#include "editor/recent_and_recovery.h"

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "editor/scene_edits.h"
#include "editor_test_util.h"
#include "renderer/project_file.h"

namespace glint {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

TEST(RecentFiles, MostRecentFirstWithoutDuplicates) {
  TempDir dir;
  std::string note;
  EXPECT_TRUE(load_recent_files(note, dir.path()).empty());
  add_recent_file("/p/a.glint", note, dir.path());
  add_recent_file("/p/b.glint", note, dir.path());
  const auto list = add_recent_file("/p/a.glint", note, dir.path());
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0], fs::path("/p/a.glint"));
  EXPECT_EQ(list[1], fs::path("/p/b.glint"));
  EXPECT_EQ(load_recent_files(note, dir.path()), list);  // persisted
  EXPECT_TRUE(fs::exists(dir / "recent.json"));
  EXPECT_EQ(note, "");
}

TEST(RecentFiles, KeepsTenAndStoresAbsolutePaths) {
  TempDir dir;
  std::string note;
  for (int k = 0; k < 15; ++k) add_recent_file("/p/f" + std::to_string(k) + ".glint", note, dir.path());
  const auto list = load_recent_files(note, dir.path());
  ASSERT_EQ(list.size(), 10u);
  EXPECT_EQ(list.front(), fs::path("/p/f14.glint"));
  EXPECT_EQ(list.back(), fs::path("/p/f5.glint"));
  const auto with_relative = add_recent_file("rel/x.glint", note, dir.path());
  EXPECT_TRUE(with_relative.front().is_absolute());
  EXPECT_EQ(with_relative.front(), (fs::current_path() / "rel/x.glint").lexically_normal());
  const auto removed = remove_recent_file("/p/f14.glint", note, dir.path());
  EXPECT_EQ(std::count(removed.begin(), removed.end(), fs::path("/p/f14.glint")), 0);
  EXPECT_EQ(load_recent_files(note, dir.path()).size(), 9u);
}

TEST(RecentFiles, CorruptFileGivesEmptyListWithANote) {
  TempDir dir;
  std::string note;
  std::ofstream(dir / "recent.json") << "{ not json";
  EXPECT_TRUE(load_recent_files(note, dir.path()).empty());
  EXPECT_NE(note.find((dir / "recent.json").string()), std::string::npos) << note;
  const auto list = add_recent_file("/p/a.glint", note, dir.path());  // and recovers from it
  EXPECT_NE(note.find("replaced"), std::string::npos) << note;
  EXPECT_EQ(list.size(), 1u);
  EXPECT_EQ(load_recent_files(note, dir.path()).size(), 1u);
  EXPECT_EQ(note, "");
}

TEST(AppState, DefaultFoldersFollowXdg) {
  // Only the path logic: nothing is written.
  const char* old = std::getenv("XDG_CONFIG_HOME");
  const std::string saved = old ? old : "";
  setenv("XDG_CONFIG_HOME", "/xdg/config", 1);
  EXPECT_EQ(recent_files_path(), fs::path("/xdg/config/glint/recent.json"));
  setenv("XDG_STATE_HOME", "/xdg/state", 1);
  EXPECT_EQ(state_dir(), fs::path("/xdg/state/glint"));
  unsetenv("XDG_STATE_HOME");
  setenv("HOME", "/home/someone", 1);
  EXPECT_EQ(state_dir(), fs::path("/home/someone/.local/state/glint"));
  EXPECT_EQ(state_dir("/explicit"), fs::path("/explicit"));
  if (old) setenv("XDG_CONFIG_HOME", saved.c_str(), 1);
  else unsetenv("XDG_CONFIG_HOME");
}

TEST(EditorSettings, PreviewExportFolderAndOrbitAreRemembered) {
  TempDir dir;
  std::string note;
  EXPECT_EQ(load_editor_settings(note, dir.path()), EditorSettings{});  // none yet: the defaults
  EXPECT_FALSE(EditorSettings{}.invert_vertical_orbit);  // Blender's orbit by default
  EditorSettings s;
  s.preview = ViewportResolution::half;
  s.export_dir = "/some/renders";
  s.invert_vertical_orbit = true;
  save_editor_settings(s, note, dir.path());
  EXPECT_TRUE(fs::exists(dir / "settings.json"));
  EXPECT_EQ(load_editor_settings(note, dir.path()), s);
  std::ofstream(dir / "settings.json") << R"({"preview": "sideways", "export_dir": 3, "invert_vertical_orbit": "yes"})";
  EXPECT_EQ(load_editor_settings(note, dir.path()), EditorSettings{});  // unknown values: defaults
  EXPECT_EQ(note, "");
  std::ofstream(dir / "settings.json") << "{ not json";
  EXPECT_EQ(load_editor_settings(note, dir.path()), EditorSettings{});
  EXPECT_NE(note.find("using the default settings"), std::string::npos) << note;
}

TEST(EditorSettings, ExportsGoToPicturesElseHomeNeverTheProject) {
  TempDir home;
  setenv("HOME", home.path().c_str(), 1);
  setenv("XDG_CONFIG_HOME", (home / ".config").c_str(), 1);
  EXPECT_EQ(default_export_dir(), home.path());
  fs::create_directories(home / "Pictures");
  EXPECT_EQ(default_export_dir(), home / "Pictures");
  // xdg-user-dirs' setting wins.
  fs::create_directories(home / "Bilder");
  fs::create_directories(home / ".config");
  std::ofstream(home / ".config/user-dirs.dirs") << "XDG_PICTURES_DIR=\"$HOME/Bilder\"\n";
  EXPECT_EQ(default_export_dir(), home / "Bilder");
}

// ---- Crash recovery.

// The names of the recovery files in `dir`, sorted (temporary files of atomic writes aside).
std::vector<std::string> recovery_files(const fs::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().filename().string().rfind("recovery", 0) == 0) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// The scene in a recovery project, read as the editor does (asset files not required).
Scene scene_in(const fs::path& file) {
  std::stringstream text;
  text << std::ifstream(file, std::ios::binary).rdbuf();
  return load_project_text(text.str(), file.string(), file.parent_path(), false);
}

// The recoveries a starting editor would offer, with no notes expected.
std::vector<Recovery> offered(const fs::path& dir) {
  std::vector<std::string> notes;
  std::vector<Recovery> found = find_recoveries(notes, dir);
  EXPECT_TRUE(notes.empty()) << notes.front();
  return found;
}

// A session that autosaves `doc` and then ends without a clean exit (as in a crash: the lock
// goes, the files stay). Returns its recovery file.
fs::path crashed_session(const Document& doc, const fs::path& dir) {
  Autosave autosave(dir, 0);
  EXPECT_TRUE(autosave.update(doc, 1)) << autosave.last_error();
  return autosave.file();
}

TEST(Recovery, NoneWhenNothingWritten) {
  TempDir dir;
  EXPECT_TRUE(offered(dir.path()).empty());
  EXPECT_TRUE(offered(dir / "missing").empty());
}

TEST(Recovery, WriteFindDiscardForSavedDocument) {
  TempDir dir;
  test::copy_asset("wood_color.png", dir / "project/assets/wood.png");
  Scene scene = new_scene();
  scene.base_dir = dir / "project";
  add_texture(scene, dir / "project/assets/wood.png");
  scene.materials[0].color_texture = scene.textures[0].name;
  Document doc(scene);
  doc.save(dir / "project/room.glint");
  add_sphere(doc.scene);  // unsaved work
  ASSERT_TRUE(doc.dirty());

  const fs::path state = dir / "state";
  const fs::path file = crashed_session(doc, state);
  EXPECT_EQ(file.parent_path(), state);
  EXPECT_EQ(file.extension(), ".glint");
  std::vector<Recovery> found = offered(state);
  ASSERT_EQ(found.size(), 1u);
  const Recovery& r = found[0];
  EXPECT_EQ(r.file, file);
  EXPECT_EQ(r.original, (dir / "project/room.glint").lexically_normal());
  EXPECT_EQ(r.scene, doc.scene);  // asset paths rebased back to the project folder
  EXPECT_EQ(r.scene.textures[0].path, "assets/wood.png");
  EXPECT_GT(r.written, 0);

  const Document restored = open_recovery(r);
  EXPECT_TRUE(restored.dirty());
  EXPECT_EQ(restored.scene.spheres.size(), 2u);
  EXPECT_EQ(restored.path(), r.original);
  EXPECT_TRUE(restored.can_undo());  // back to the file as saved

  discard_recovery(r);
  found.clear();
  EXPECT_TRUE(offered(state).empty());
  EXPECT_TRUE(recovery_files(state).empty());  // the scene, the sidecar and the lock file
}

TEST(Recovery, UntitledDocumentRecoversDirty) {
  TempDir dir;
  Document doc;
  add_quad(doc.scene);
  crashed_session(doc, dir.path());
  const auto found = offered(dir.path());
  ASSERT_EQ(found.size(), 1u);
  EXPECT_TRUE(found[0].original.empty());
  const Document restored = open_recovery(found[0]);
  EXPECT_TRUE(restored.path().empty());
  EXPECT_TRUE(restored.dirty());
  EXPECT_EQ(restored.scene.quads.size(), 2u);
}

TEST(Recovery, CorruptRecoveryIsNotedAndKept) {
  TempDir dir;
  const fs::path file = dir / "recovery-00000000000000aa.glint";
  std::ofstream(file) << "{\"format\": \"glint-project\", \"vers";
  std::vector<std::string> notes;
  EXPECT_TRUE(find_recoveries(notes, dir.path()).empty());
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find(file.string()), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("not offered"), std::string::npos) << notes[0];
  EXPECT_TRUE(fs::exists(file));
}

TEST(Recovery, AutosaveWritesWhileDirtyAndCleansUpAfterSave) {
  TempDir dir;
  const fs::path state = dir / "state";
  Autosave autosave(state, /*interval_s=*/5);
  Document doc;
  EXPECT_FALSE(autosave.update(doc, 0));  // clean: nothing to save
  EXPECT_TRUE(autosave.file().empty());
  EXPECT_TRUE(recovery_files(state).empty());

  add_sphere(doc.scene);
  EXPECT_TRUE(autosave.update(doc, 1));
  const fs::path file = autosave.file();
  EXPECT_EQ(scene_in(file).spheres.size(), 2u);
  add_sphere(doc.scene);
  EXPECT_FALSE(autosave.update(doc, 3));  // within the interval
  EXPECT_EQ(scene_in(file).spheres.size(), 2u);
  EXPECT_TRUE(autosave.update(doc, 6.5));
  EXPECT_EQ(scene_in(file).spheres.size(), 3u);
  EXPECT_FALSE(autosave.update(doc, 20));  // unchanged since the last write
  EXPECT_TRUE(offered(state).empty());     // this session is running: its work is not offered

  doc.save(dir / "saved.glint");
  autosave.update(doc, 21);
  EXPECT_FALSE(fs::exists(file));  // clean again: the recovery is stale
  EXPECT_FALSE(fs::exists(fs::path(file).replace_extension(".json")));

  add_sphere(doc.scene);
  autosave.update(doc, 40);
  EXPECT_TRUE(fs::exists(autosave.file()));
  autosave.finish();  // clean exit
  EXPECT_TRUE(recovery_files(state).empty());
  EXPECT_TRUE(offered(state).empty());
}

TEST(Recovery, AutosaveLeavesAForeignRecoveryAlone) {
  TempDir dir;
  Document crashed;
  add_sphere(crashed.scene);
  const fs::path crashed_file = crashed_session(crashed, dir.path());
  Autosave autosave(dir.path());
  Document fresh;
  autosave.update(fresh, 100);  // clean document: must not delete what it did not write
  add_quad(fresh.scene);
  autosave.update(fresh, 101);  // its own file, beside the crashed one
  EXPECT_NE(autosave.file(), crashed_file);
  EXPECT_EQ(scene_in(crashed_file).spheres.size(), 2u);
  autosave.finish();  // a clean exit with the offer unanswered: it stays for the next start
  const auto found = offered(dir.path());
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].file, crashed_file);
}

// Two editors open at once: each autosaves to its own files, neither offers the other's work
// while it runs, and when one crashes only its work is offered, while the other goes on.
TEST(Recovery, TwoSessionsKeepTheirOwnRecoveries) {
  TempDir dir;
  Document doc_a, doc_b;
  add_sphere(doc_a.scene);
  add_quad(doc_b.scene);
  auto a = std::make_unique<Autosave>(dir.path(), 0);
  Autosave b(dir.path(), 0);
  ASSERT_TRUE(a->update(doc_a, 1)) << a->last_error();
  ASSERT_TRUE(b.update(doc_b, 1)) << b.last_error();
  const fs::path file_a = a->file();
  ASSERT_NE(file_a, b.file());
  EXPECT_EQ(scene_in(file_a).spheres.size(), 2u);  // not overwritten by b
  EXPECT_EQ(scene_in(b.file()).quads.size(), 2u);

  // A third editor starting now offers neither: both are running.
  EXPECT_TRUE(offered(dir.path()).empty());

  a.reset();  // a crashes
  std::vector<Recovery> found = offered(dir.path());
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].file, file_a);
  EXPECT_EQ(found[0].scene.spheres.size(), 2u);
  add_quad(doc_b.scene);
  EXPECT_TRUE(b.update(doc_b, 2));  // b goes on, untouched
  EXPECT_EQ(scene_in(b.file()).quads.size(), 3u);
  discard_recovery(found[0]);
  EXPECT_TRUE(fs::exists(b.file()));
  b.finish();
  EXPECT_TRUE(recovery_files(dir.path()).empty());
}

// The same with real processes: a child autosaves and waits; while it lives its recovery is
// not offered; killed (SIGKILL: no clean exit), its recovery is.
TEST(Recovery, KilledEditorsRecoveryIsOfferedALiveOnesIsNot) {
  TempDir dir;
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(ready[0]);
    Document doc;
    add_sphere(doc.scene);
    add_sphere(doc.scene);
    Autosave autosave(dir.path(), 0);
    const char ok = autosave.update(doc, 1) ? 'y' : 'n';
    [[maybe_unused]] const ssize_t n = ::write(ready[1], &ok, 1);
    for (;;) ::pause();
  }
  ::close(ready[1]);
  char ok = 0;
  ASSERT_EQ(::read(ready[0], &ok, 1), 1);
  ::close(ready[0]);
  EXPECT_EQ(ok, 'y');
  EXPECT_TRUE(offered(dir.path()).empty());  // the child is running
  ASSERT_EQ(recovery_files(dir.path()).size(), 3u);  // its .glint, .json and .lock stay put
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  const auto found = offered(dir.path());
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].scene.spheres.size(), 3u);
}

// A recovery on offer is held by the editor offering it: another editor starting meanwhile
// neither offers nor deletes it; unanswered, it is offered again later.
TEST(Recovery, AnOfferedRecoveryIsHeldUntilAnswered) {
  TempDir dir;
  Document doc;
  add_sphere(doc.scene);
  const fs::path file = crashed_session(doc, dir.path());
  std::vector<Recovery> first = offered(dir.path());
  ASSERT_EQ(first.size(), 1u);
  EXPECT_TRUE(offered(dir.path()).empty());
  first.clear();  // left unanswered (a clean exit)
  std::vector<Recovery> again = offered(dir.path());
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].file, file);
}

// Every orphan is offered, newest first.
TEST(Recovery, EveryOrphanIsOfferedNewestFirst) {
  TempDir dir;
  std::vector<fs::path> files;
  for (int k = 0; k < 3; ++k) {
    Document doc;
    for (int i = 0; i <= k; ++i) add_sphere(doc.scene);
    files.push_back(crashed_session(doc, dir.path()));
    const auto when = fs::file_time_type::clock::now() - std::chrono::hours(3 - k);
    fs::last_write_time(files.back(), when);
  }
  const auto found = offered(dir.path());
  ASSERT_EQ(found.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(found[k].file, files[2 - k]);
    EXPECT_EQ(found[k].scene.spheres.size(), size_t(4 - k));
  }
}

// The one fixed-name recovery of older editors (recovery.glint and recovery.json) is offered
// like the others and discarded with its lock file.
TEST(Recovery, AnOlderEditorsRecoveryIsOffered) {
  TempDir dir;
  Document doc;
  add_quad(doc.scene);
  doc.save(dir / "room.glint");
  add_sphere(doc.scene);
  fs::create_directories(dir / "state");
  save_project(doc.scene, dir / "state/recovery.glint");
  std::ofstream(dir / "state/recovery.json")
      << R"({"original": ")" << (dir / "room.glint").string() << R"(", "base_dir": ")" << dir.path().string()
      << "\"}\n";
  std::vector<Recovery> found = offered(dir / "state");
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].file, dir / "state/recovery.glint");
  EXPECT_EQ(found[0].original, dir / "room.glint");
  EXPECT_EQ(found[0].scene, doc.scene);
  EXPECT_TRUE(offered(dir / "state").empty());  // held while on offer
  discard_recovery(found[0]);
  EXPECT_TRUE(recovery_files(dir / "state").empty());
}

// A session's leftovers with nothing to recover (it crashed with no unsaved changes) go; a
// running session's lock file stays.
TEST(Recovery, LeftoversWithoutARecoveryAreRemoved) {
  TempDir dir;
  std::ofstream(dir / "recovery-0123456789abcdef.lock") << "";
  std::ofstream(dir / "recovery-0123456789abcdef.json") << "{}";
  std::ofstream(dir / "recovery-fedcba9876543210.lock") << "";
  std::ofstream(dir / "recovery-notes.txt") << "not ours";
  Autosave running(dir.path(), 0);
  Document doc;
  add_sphere(doc.scene);
  ASSERT_TRUE(running.update(doc, 1));
  doc.save(dir / "saved.glint");
  running.update(doc, 2);  // saved: its recovery goes, its lock stays held
  const fs::path running_lock = fs::path(running.file()).replace_extension(".lock");
  EXPECT_TRUE(offered(dir.path()).empty());
  EXPECT_EQ(recovery_files(dir.path()), (std::vector<std::string>{running_lock.filename().string(), "recovery-notes.txt"}));
}

}  // namespace
}  // namespace glint
