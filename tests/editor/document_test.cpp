// The document: dirty tracking, window title, derived undo/redo, save and open.
#include "editor/document.h"

#include <gtest/gtest.h>

#include <vector>

#include "editor/scene_edits.h"
#include "editor_test_util.h"
#include "renderer/project_file.h"

namespace glint {
namespace {

using test::problems;
using test::TempDir;

TEST(Document, NewSceneIsValidAndAsSpecified) {
  const Scene s = new_scene();
  EXPECT_EQ(problems(s), "");
  ASSERT_EQ(s.spheres.size(), 1u);
  ASSERT_EQ(s.quads.size(), 1u);
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.camera.target, s.spheres[0].center);  // looks at the sphere
  // Grey matte and white glossy materials.
  EXPECT_EQ(s.materials[0].type, MaterialType::matte);
  EXPECT_EQ(s.materials[1].type, MaterialType::glossy);
  EXPECT_EQ(s.environment.color, glm::vec3(0.5f));
  // The floor faces up, under the sphere.
  const Quad& q = s.quads[0];
  const glm::vec3 n = glm::normalize(glm::cross(q.corners[1] - q.corners[0], q.corners[2] - q.corners[0]));
  EXPECT_GT(n.y, 0.99f);
  EXPECT_LE(q.corners[0].y, s.spheres[0].center.y - s.spheres[0].radius);
}

TEST(Document, TitleShowsNameAndUnsavedMark) {
  Document doc;
  EXPECT_FALSE(doc.dirty());
  EXPECT_EQ(doc.display_name(), "Untitled");
  EXPECT_EQ(doc.window_title(), "Untitled - Glint");
  add_sphere(doc.scene);
  EXPECT_TRUE(doc.dirty());
  EXPECT_EQ(doc.window_title(), "Untitled* - Glint");

  Document named(new_scene(), "/some/folder/room.glint");
  EXPECT_EQ(named.window_title(), "room.glint - Glint");
  named.scene.spheres[0].radius = 2;
  EXPECT_EQ(named.window_title(), "room.glint* - Glint");
}

TEST(Document, AddMoveDeleteEachUndoAndRedo) {
  Document doc;
  const Scene original = doc.scene;
  // Add.
  const int i = add_sphere(doc.scene);
  doc.end_frame(false);
  const Scene added = doc.scene;
  ASSERT_EQ(added.spheres.size(), 2u);
  // Move.
  translate(doc.scene, {SelectionKind::sphere, i}, {1, 0, 0});
  doc.end_frame(false);
  const Scene moved = doc.scene;
  EXPECT_EQ(moved.spheres[1].center, added.spheres[1].center + glm::vec3(1, 0, 0));
  // Delete.
  doc.selection = remove(doc.scene, {SelectionKind::sphere, i});
  doc.end_frame(false);
  EXPECT_EQ(doc.scene.spheres.size(), 1u);

  doc.undo();
  EXPECT_EQ(doc.scene, moved);
  doc.undo();
  EXPECT_EQ(doc.scene, added);
  doc.undo();
  EXPECT_EQ(doc.scene, original);
  EXPECT_FALSE(doc.can_undo());
  EXPECT_FALSE(doc.dirty());
  doc.redo();
  doc.redo();
  EXPECT_EQ(doc.scene, moved);
  doc.redo();
  EXPECT_EQ(doc.scene.spheres.size(), 1u);
  EXPECT_FALSE(doc.can_redo());
}

TEST(Document, UndoLeavesNothingToCommit) {
  Document doc;
  add_sphere(doc.scene);
  doc.end_frame(false);
  doc.undo();
  doc.end_frame(false);  // must not record the undo as a new edit
  EXPECT_TRUE(doc.can_redo());
  EXPECT_FALSE(doc.can_undo());
  doc.redo();
  doc.end_frame(false);
  EXPECT_TRUE(doc.can_undo());
  EXPECT_FALSE(doc.can_redo());
}

TEST(Document, DragOfManyFramesIsOneUndoStep) {
  Document doc;
  const glm::vec3 start = doc.scene.spheres[0].center;
  for (int frame = 0; frame < 30; ++frame) {
    translate(doc.scene, {SelectionKind::sphere, 0}, {0.1f, 0, 0});
    doc.end_frame(/*interacting=*/true);
    EXPECT_FALSE(doc.can_undo()) << "frame " << frame;
  }
  doc.end_frame(false);  // mouse released
  EXPECT_TRUE(doc.can_undo());
  doc.undo();
  EXPECT_EQ(doc.scene.spheres[0].center, start);
  EXPECT_FALSE(doc.can_undo());
}

TEST(Document, NewEditClearsRedo) {
  Document doc;
  add_sphere(doc.scene);
  doc.end_frame(false);
  doc.undo();
  EXPECT_TRUE(doc.can_redo());
  add_quad(doc.scene);
  doc.end_frame(false);
  EXPECT_FALSE(doc.can_redo());
  EXPECT_EQ(doc.scene.quads.size(), 2u);
  EXPECT_EQ(doc.scene.spheres.size(), 1u);
}

TEST(Document, UndoRestoresSelection) {
  Document doc;
  doc.selection = {SelectionKind::sphere, 0};
  doc.end_frame(false);
  doc.selection = remove(doc.scene, doc.selection);
  doc.end_frame(false);
  EXPECT_EQ(doc.selection.kind, SelectionKind::none);
  doc.undo();
  EXPECT_EQ(doc.selection, (Selection{SelectionKind::sphere, 0}));
  EXPECT_EQ(doc.scene.spheres.size(), 1u);
}

TEST(Document, UndoDepthIsCapped) {
  Document doc;
  for (int k = 0; k < 250; ++k) {
    translate(doc.scene, {SelectionKind::sphere, 0}, {0.01f, 0, 0});
    doc.end_frame(false);
  }
  int steps = 0;
  while (doc.can_undo() && steps < 1000) {
    doc.undo();
    ++steps;
  }
  EXPECT_GE(steps, 100);
  EXPECT_LE(steps, 200);
}

TEST(Document, SaveThenOpenRoundTrip) {
  TempDir dir;
  test::copy_asset("wood_color.png", dir / "assets/wood.png");
  Document doc(new_scene());
  doc.scene.base_dir = dir.path();
  const int t = add_texture(doc.scene, dir / "assets/wood.png");
  doc.scene.materials[0].color_texture = doc.scene.textures[static_cast<size_t>(t)].name;
  add_sphere(doc.scene);
  doc.end_frame(false);
  ASSERT_EQ(problems(doc.scene, true), "");

  const auto file = dir / "scene.glint";
  doc.save(file);
  EXPECT_FALSE(doc.dirty());
  EXPECT_EQ(doc.path(), file);
  EXPECT_EQ(doc.window_title(), "scene.glint - Glint");
  const Scene loaded = load_project(file);
  EXPECT_EQ(loaded, doc.scene);
  EXPECT_EQ(doc.scene.textures[0].path, "assets/wood.png");

  Document reopened(loaded, file);
  EXPECT_FALSE(reopened.dirty());
}

TEST(Document, SaveAsAnotherFolderKeepsTexturesResolvable) {
  TempDir dir;
  test::copy_asset("wood_color.png", dir / "a/assets/wood.png");
  Document doc(new_scene());
  doc.scene.base_dir = dir / "a";
  add_texture(doc.scene, dir / "a/assets/wood.png");
  doc.scene.materials[0].color_texture = doc.scene.textures[0].name;
  doc.save(dir / "a/scene.glint");

  std::filesystem::create_directories(dir / "b/deeper");
  const auto other = dir / "b/deeper/copy.glint";
  doc.save(other);
  EXPECT_EQ(doc.path(), other);
  EXPECT_EQ(doc.scene.base_dir, other.parent_path());
  EXPECT_EQ(doc.scene.textures[0].path, "../../a/assets/wood.png");
  EXPECT_EQ(problems(doc.scene, true), "");
  const Scene loaded = load_project(other);  // checks the image files exist
  EXPECT_EQ(loaded, doc.scene);
}

TEST(Document, UndoAfterSaveMakesDirtyAgain) {
  TempDir dir;
  Document doc;
  translate(doc.scene, {SelectionKind::sphere, 0}, {0, 1, 0});
  doc.end_frame(false);
  doc.save(dir / "x.glint");
  EXPECT_FALSE(doc.dirty());
  doc.undo();
  EXPECT_TRUE(doc.dirty());
  EXPECT_EQ(doc.window_title(), "x.glint* - Glint");
  doc.redo();
  EXPECT_FALSE(doc.dirty());
}

TEST(Document, SaveCommitsAPendingEdit) {
  TempDir dir;
  Document doc;
  add_sphere(doc.scene);  // no end_frame before the save (Ctrl+S in the same frame)
  doc.save(dir / "x.glint");
  EXPECT_TRUE(doc.can_undo());
  doc.undo();
  EXPECT_EQ(doc.scene.spheres.size(), 1u);
}

TEST(Document, FailedSaveThrowsAndStaysDirty) {
  TempDir dir;
  Document doc;
  add_sphere(doc.scene);
  EXPECT_THROW(doc.save(dir / "no/such/folder/x.glint"), ProjectError);
  EXPECT_TRUE(doc.dirty());
  EXPECT_TRUE(doc.path().empty());
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

TEST(Document, ARunOfCameraMovesIsOneUndoStep) {
  Document doc;
  const Scene original = doc.scene;
  doc.scene.spheres[0].radius = 0.7f;  // a scene edit
  doc.end_frame(false);
  const Scene edited = doc.scene;
  for (int i = 0; i < 30; ++i) {  // thirty separate orbit gestures
    doc.scene.camera.position.x += 0.1f;
    doc.end_frame(false, /*navigated=*/true);
  }
  const Scene orbited = doc.scene;
  doc.undo();  // all camera moves at once
  EXPECT_EQ(doc.scene, edited);
  doc.undo();  // then the edit
  EXPECT_EQ(doc.scene, original);
  EXPECT_FALSE(doc.can_undo());
  doc.redo();
  doc.redo();
  EXPECT_EQ(doc.scene, orbited);
  // An edit ends the run: the camera moves after it are a step of their own.
  doc.scene.spheres[0].radius = 0.9f;
  doc.end_frame(false);
  const Scene edited_again = doc.scene;
  doc.scene.camera.position.y += 0.5f;
  doc.end_frame(false, true);
  doc.undo();
  EXPECT_EQ(doc.scene, edited_again);
  doc.undo();
  EXPECT_EQ(doc.scene, orbited);
}

// Only navigation merges: a typed field of view, a typed aperture and a click-to-focus (camera
// changes that are not navigation) are a step each, and navigation after them a step of its own.
TEST(Document, DeliberateCameraSettingsAreStepsOfTheirOwn) {
  Document doc;
  std::vector<Scene> states{doc.scene};
  doc.scene.camera.position.x += 0.3f;  // an orbit: navigation
  doc.end_frame(false, true);
  states.push_back(doc.scene);
  doc.scene.camera.vfov_deg = 55;  // typed
  doc.end_frame(false);
  states.push_back(doc.scene);
  doc.scene.camera.aperture_radius = 0.05f;  // typed
  doc.end_frame(false);
  states.push_back(doc.scene);
  doc.scene.camera.focus_distance = 3.25f;  // a click-to-focus
  doc.end_frame(false);
  states.push_back(doc.scene);
  for (int i = 0; i < 5; ++i) {  // an orbit drag over several frames, then released
    doc.scene.camera.position.x += 0.1f;
    doc.end_frame(/*interacting=*/true, true);
  }
  doc.end_frame(false);
  doc.scene.camera.position.y += 0.2f;  // a zoom right after: the same run of navigation
  doc.end_frame(false, true);
  states.push_back(doc.scene);
  for (size_t i = states.size() - 1; i > 0; --i) {
    ASSERT_TRUE(doc.can_undo()) << i;
    doc.undo();
    EXPECT_EQ(doc.scene, states[i - 1]) << "undo step " << states.size() - i;
  }
  EXPECT_FALSE(doc.can_undo());
}

}  // namespace
}  // namespace glint
