// Recent files and crash recovery, in a temporary folder instead of $HOME.
#include "editor/recent_and_recovery.h"

#include <fstream>

#include <gtest/gtest.h>

#include "editor/scene_edits.h"
#include "editor_test_util.h"

namespace glint {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

TEST(RecentFiles, MostRecentFirstWithoutDuplicates) {
  TempDir dir;
  EXPECT_TRUE(load_recent_files(dir.path()).empty());
  add_recent_file("/p/a.glint", dir.path());
  add_recent_file("/p/b.glint", dir.path());
  const auto list = add_recent_file("/p/a.glint", dir.path());
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0], fs::path("/p/a.glint"));
  EXPECT_EQ(list[1], fs::path("/p/b.glint"));
  EXPECT_EQ(load_recent_files(dir.path()), list);  // persisted
  EXPECT_TRUE(fs::exists(dir / "recent.json"));
}

TEST(RecentFiles, KeepsTenAndStoresAbsolutePaths) {
  TempDir dir;
  for (int k = 0; k < 15; ++k) add_recent_file("/p/f" + std::to_string(k) + ".glint", dir.path());
  const auto list = load_recent_files(dir.path());
  ASSERT_EQ(list.size(), 10u);
  EXPECT_EQ(list.front(), fs::path("/p/f14.glint"));
  EXPECT_EQ(list.back(), fs::path("/p/f5.glint"));
  const auto with_relative = add_recent_file("rel/x.glint", dir.path());
  EXPECT_TRUE(with_relative.front().is_absolute());
  EXPECT_EQ(with_relative.front(), (fs::current_path() / "rel/x.glint").lexically_normal());
  const auto removed = remove_recent_file("/p/f14.glint", dir.path());
  EXPECT_EQ(std::count(removed.begin(), removed.end(), fs::path("/p/f14.glint")), 0);
  EXPECT_EQ(load_recent_files(dir.path()).size(), 9u);
}

TEST(RecentFiles, CorruptFileGivesEmptyList) {
  TempDir dir;
  std::ofstream(dir / "recent.json") << "{ not json";
  EXPECT_TRUE(load_recent_files(dir.path()).empty());
  const auto list = add_recent_file("/p/a.glint", dir.path());  // and recovers from it
  EXPECT_EQ(list.size(), 1u);
  EXPECT_EQ(load_recent_files(dir.path()).size(), 1u);
}

TEST(AppState, DefaultFoldersFollowXdg) {
  // Only the path logic: nothing is written.
  const char* old = std::getenv("XDG_CONFIG_HOME");
  const std::string saved = old ? old : "";
  setenv("XDG_CONFIG_HOME", "/xdg/config", 1);
  EXPECT_EQ(recent_files_path(), fs::path("/xdg/config/glint/recent.json"));
  setenv("XDG_STATE_HOME", "/xdg/state", 1);
  EXPECT_EQ(recovery_file_path(), fs::path("/xdg/state/glint/recovery.glint"));
  unsetenv("XDG_STATE_HOME");
  setenv("HOME", "/home/someone", 1);
  EXPECT_EQ(state_dir(), fs::path("/home/someone/.local/state/glint"));
  EXPECT_EQ(state_dir("/explicit"), fs::path("/explicit"));
  if (old) setenv("XDG_CONFIG_HOME", saved.c_str(), 1);
  else unsetenv("XDG_CONFIG_HOME");
}

TEST(EditorSettings, PreviewAndExportFolderAreRemembered) {
  TempDir dir;
  EXPECT_EQ(load_editor_settings(dir.path()), EditorSettings{});  // none yet: the defaults
  EditorSettings s;
  s.preview = ViewportResolution::half;
  s.export_dir = "/some/renders";
  save_editor_settings(s, dir.path());
  EXPECT_TRUE(fs::exists(dir / "settings.json"));
  EXPECT_EQ(load_editor_settings(dir.path()), s);
  std::ofstream(dir / "settings.json") << R"({"preview": "sideways", "export_dir": 3})";
  EXPECT_EQ(load_editor_settings(dir.path()), EditorSettings{});  // unknown values: defaults
  std::ofstream(dir / "settings.json") << "{ not json";
  EXPECT_EQ(load_editor_settings(dir.path()), EditorSettings{});
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

TEST(Recovery, NoneWhenNothingWritten) {
  TempDir dir;
  EXPECT_FALSE(find_recovery(dir.path()));
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
  write_recovery(doc, state);
  EXPECT_TRUE(fs::exists(state / "recovery.glint"));
  const std::optional<Recovery> r = find_recovery(state);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->original, (dir / "project/room.glint").lexically_normal());
  EXPECT_EQ(r->scene, doc.scene);  // asset paths rebased back to the project folder
  EXPECT_EQ(r->scene.textures[0].path, "assets/wood.png");

  const Document restored = open_recovery(*r);
  EXPECT_TRUE(restored.dirty());
  EXPECT_EQ(restored.scene.spheres.size(), 2u);
  EXPECT_EQ(restored.path(), r->original);
  EXPECT_TRUE(restored.can_undo());  // back to the file as saved

  discard_recovery(state);
  EXPECT_FALSE(find_recovery(state));
  EXPECT_FALSE(fs::exists(state / "recovery.json"));
}

TEST(Recovery, UntitledDocumentRecoversDirty) {
  TempDir dir;
  Document doc;
  add_quad(doc.scene);
  write_recovery(doc, dir.path());
  const auto r = find_recovery(dir.path());
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->original.empty());
  const Document restored = open_recovery(*r);
  EXPECT_TRUE(restored.path().empty());
  EXPECT_TRUE(restored.dirty());
  EXPECT_EQ(restored.scene.quads.size(), 2u);
}

TEST(Recovery, CorruptRecoveryIsIgnored) {
  TempDir dir;
  std::ofstream(dir / "recovery.glint") << "{\"format\": \"glint-project\", \"vers";
  EXPECT_FALSE(find_recovery(dir.path()));
}

TEST(Recovery, AutosaveWritesWhileDirtyAndCleansUpAfterSave) {
  TempDir dir;
  const fs::path state = dir / "state";
  Autosave autosave(state, /*interval_s=*/5);
  Document doc;
  EXPECT_FALSE(autosave.update(doc, 0));  // clean: nothing to save
  EXPECT_FALSE(find_recovery(state));

  add_sphere(doc.scene);
  EXPECT_TRUE(autosave.update(doc, 1));
  EXPECT_EQ(find_recovery(state)->scene.spheres.size(), 2u);
  add_sphere(doc.scene);
  EXPECT_FALSE(autosave.update(doc, 3));  // within the interval
  EXPECT_EQ(find_recovery(state)->scene.spheres.size(), 2u);
  EXPECT_TRUE(autosave.update(doc, 6.5));
  EXPECT_EQ(find_recovery(state)->scene.spheres.size(), 3u);
  EXPECT_FALSE(autosave.update(doc, 20));  // unchanged since the last write

  doc.save(dir / "saved.glint");
  autosave.update(doc, 21);
  EXPECT_FALSE(find_recovery(state));  // clean again: the recovery is stale

  add_sphere(doc.scene);
  autosave.update(doc, 40);
  EXPECT_TRUE(find_recovery(state));
  autosave.finish();  // clean exit
  EXPECT_FALSE(find_recovery(state));
}

TEST(Recovery, AutosaveLeavesAForeignRecoveryAlone) {
  TempDir dir;
  Document crashed;
  add_sphere(crashed.scene);
  write_recovery(crashed, dir.path());  // from the run that crashed
  Autosave autosave(dir.path());
  Document fresh;
  autosave.update(fresh, 100);  // clean document: must not delete what it did not write
  EXPECT_TRUE(find_recovery(dir.path()));
  autosave.finish();  // a clean exit with the offer unanswered: it stays for the next start
  EXPECT_TRUE(find_recovery(dir.path()));
}

}  // namespace
}  // namespace glint
