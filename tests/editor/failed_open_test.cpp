// A failed open leaves the open document as it was: scene, file, selection, unsaved changes
// and undo history (open_document loads the whole project before it replaces anything).
#include <gtest/gtest.h>

#include <fstream>

#include "editor/document.h"
#include "editor/scene_edits.h"
#include "editor/ui.h"
#include "editor_test_util.h"
#include "tests/image_fixtures.h"

namespace glint {
namespace {

using test::TempDir;

TEST(FailedOpen, LeavesThePreviousDocumentUntouched) {
  TempDir dir;
  Document doc(new_scene(), dir / "current.glint");
  add_sphere(doc.scene);
  doc.selection = {SelectionKind::sphere, 1};
  doc.end_frame(false);
  const Scene after_add = doc.scene;
  doc.scene.spheres[1].radius = 0.25f;  // an edit not yet committed to the undo history
  ASSERT_TRUE(doc.dirty());
  ASSERT_TRUE(doc.can_undo());
  const Scene scene_before = doc.scene;

  // Broken in different ways: bad JSON, a bad value deep inside, a missing texture, no file.
  const std::vector<std::pair<std::string, std::string>> files = {
      {"truncated.glint", R"({"format": "glint-project", "version": 1, "spheres": [{"cen)"},
      {"radius.glint", R"({"format": "glint-project", "version": 1, "materials": [{"name": "m"}],
        "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "m"},
                    {"center": [0, 0, 0], "radius": -1, "material": "m"}]})"},
      {"texture.glint", R"({"format": "glint-project", "version": 1,
        "textures": [{"name": "t", "path": "missing.png"}]})"},
      {"decode.glint", R"({"format": "glint-project", "version": 1,
        "textures": [{"name": "t", "path": "short.png"}]})"},
  };
  // Passes the header probe, fails to decode: found on open, not when first rendered.
  test::write_png_with_short_idat(dir / "short.png");
  for (const auto& [name, text] : files) std::ofstream(dir / name) << text;
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"truncated.glint", "invalid JSON"},
      {"radius.glint", "spheres[1].radius: must be greater than 0 (got -1)"},
      {"texture.glint", "textures[0].path: cannot read image"},
      {"decode.glint", "textures[0].path: cannot read image: " + (dir / "short.png").string() +
                           ": cannot decode image"},
      {"absent.glint", "no such file"},
  };
  EditorState state;
  for (const auto& [name, problem] : expected) {
    SCOPED_TRACE(name);
    state.messages.error.clear();
    EXPECT_FALSE(open_document(doc, state, dir / name));
    EXPECT_NE(state.messages.error.find((dir / name).string()), std::string::npos) << state.messages.error;
    EXPECT_NE(state.messages.error.find(problem), std::string::npos) << state.messages.error;
    EXPECT_TRUE(state.messages.open_error);
    EXPECT_EQ(doc.scene, scene_before);
    EXPECT_EQ(doc.path(), dir / "current.glint");
    EXPECT_EQ(doc.selection, (Selection{SelectionKind::sphere, 1}));
    EXPECT_TRUE(doc.dirty());
  }
  // The history is intact: the uncommitted edit commits, then undo goes back step by step.
  doc.end_frame(false);
  doc.undo();
  EXPECT_EQ(doc.scene, after_add);
  doc.undo();
  EXPECT_EQ(doc.scene, new_scene());
  EXPECT_FALSE(doc.can_undo());
}

}  // namespace
}  // namespace glint
