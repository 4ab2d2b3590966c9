// File > Import scene... / Export scene... (editor/ui_scene_exchange.cpp): an export writes the
// document as Mitsuba or pbrt, an import opens one as an untitled document, a failure leaves
// the document as it was.
#include <gtest/gtest.h>

#include <fstream>

#include <imgui.h>

#include "editor/document.h"
#include "editor/ui.h"
#include "editor_test_util.h"
#include "renderer/project_file.h"

namespace glint {
namespace {

using test::TempDir;

// The status bar's messages take ImGui's clock.
struct ImGuiContextScope {
  ImGuiContextScope() { ImGui::CreateContext(); }
  ~ImGuiContextScope() { ImGui::DestroyContext(); }
};

TEST(SceneExchangeMenu, ExportsAndImportsThroughTheFileDialogPurposes) {
  ImGuiContextScope imgui;
  TempDir dir;
  const std::filesystem::path project = std::filesystem::path(GLINT_SOURCE_DIR) / "projects/cornell_box.glint";
  Document doc(load_project(project), project);
  EditorState state;
  for (const char* name : {"box.xml", "box.pbrt"}) {
    SCOPED_TRACE(name);
    apply_chosen_file(doc, state, FilePurpose::export_scene, (dir / name).string());
    EXPECT_TRUE(state.messages.error.empty()) << state.messages.error;
    ASSERT_TRUE(std::filesystem::exists(dir / name));
    Document imported;
    apply_chosen_file(imported, state, FilePurpose::import_scene, (dir / name).string());
    EXPECT_TRUE(state.messages.error.empty()) << state.messages.error;
    EXPECT_TRUE(imported.path().empty()) << "an import is untitled until saved as a project";
    EXPECT_EQ(imported.scene.spheres.size(), doc.scene.spheres.size());
    EXPECT_EQ(imported.scene.quads.size(), doc.scene.quads.size());
    EXPECT_NE(state.messages.note.find("warning"), std::string::npos) << state.messages.note;
  }
}

TEST(SceneExchangeMenu, AFailedImportLeavesTheDocument) {
  ImGuiContextScope imgui;
  TempDir dir;
  std::ofstream(dir / "bad.pbrt") << "WorldBegin\nShape \"sphere\" \"float radius\" [ -x ]\n";
  Document doc(new_scene(), dir / "current.glint");
  const Scene before = doc.scene;
  EditorState state;
  EXPECT_FALSE(import_document(doc, state, dir / "bad.pbrt"));
  EXPECT_NE(state.messages.error.find("bad.pbrt: line 2: Shape \"float radius\": expected a number"), std::string::npos)
      << state.messages.error;
  EXPECT_EQ(doc.scene, before);
  EXPECT_EQ(doc.path(), dir / "current.glint");
  state.messages.error.clear();
  EXPECT_FALSE(export_document(doc, state, dir / "x.obj"));
  EXPECT_NE(state.messages.error.find("must end in .xml (Mitsuba 3) or .pbrt"), std::string::npos) << state.messages.error;
}

}  // namespace
}  // namespace glint
