// The export dialog's time left and first output folder.
#include <gtest/gtest.h>

#include "editor/ui.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

TEST(ExportEta, FromTheFractionDoneAndTheTimeSoFar) {
  EXPECT_EQ(export_eta(0.0, 3.0), "estimating time left");  // nothing to extrapolate from yet
  EXPECT_EQ(export_eta(0.5, 0.1), "estimating time left");
  EXPECT_EQ(export_eta(0.25, 10.0), "about 30 s left");     // 10 s per quarter, three to go
  EXPECT_EQ(export_eta(0.1, 60.0), "about 9 min 00 s left");
  EXPECT_EQ(export_eta(0.02, 3600.0), "about 49 h 00 min left");
}

TEST(ExportEta, FirstFolderIsTheRememberedOneElsePicturesNeverTheProject) {
  test::TempDir home;
  setenv("HOME", home.path().c_str(), 1);
  setenv("XDG_CONFIG_HOME", (home / ".config").c_str(), 1);
  std::filesystem::create_directories(home / "Pictures");
  Document doc(new_scene(), home / "repo/scene.glint");
  EditorState state;
  ExportSettings s = default_export_settings(doc, state);
  EXPECT_EQ(s.output, home / "Pictures/scene.png");
  EXPECT_EQ(s.width, doc.scene.film.width);
  std::filesystem::create_directories(home / "renders");
  state.settings.export_dir = home / "renders";
  EXPECT_EQ(default_export_settings(doc, state).output, home / "renders/scene.png");
  state.settings.export_dir = home / "gone";  // a remembered folder that no longer exists
  EXPECT_EQ(default_export_settings(doc, state).output, home / "Pictures/scene.png");
}

}  // namespace
}  // namespace glint
