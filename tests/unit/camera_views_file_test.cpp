// Camera views in the project file (Scene::views, docs/DESIGN.md §6): optional, written only
// when there are some, read and checked as the camera is, and in no digest.
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <iterator>
#include <string>

#include "renderer/project_file.h"
#include "renderer/scene_digest.h"
#include "renderer/scene_validation.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

const fs::path kProjects = fs::path(GLINT_SOURCE_DIR) / "projects";

Scene with_views() {
  Scene s = load_project(kProjects / "default.glint");
  Camera top = s.camera;
  top.position = {0, 8, 0.01f};
  s.views = {{"Front", s.camera}, {"Top", top}};
  return s;
}

// The error loading `doc` gives ("" when it loads).
std::string load_error(const Json& doc) {
  try {
    load_project_text(doc.dump(), "views.glint", kProjects, false);
  } catch (const ProjectError& e) {
    return e.what();
  }
  return "";
}

TEST(CameraViewsFile, AProjectWithoutViewsLoadsAndSavesAsBefore) {
  std::ifstream in(kProjects / "default.glint", std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(text.find("\"views\""), std::string::npos);
  const Scene s = load_project_text(text, "default.glint", kProjects, false);
  EXPECT_TRUE(s.views.empty());
  // Written without the key, so that older versions (which refuse unknown keys) still read it.
  EXPECT_EQ(project_file_text(s).find("\"views\""), std::string::npos);
}

TEST(CameraViewsFile, ViewsAreWrittenAndReadBackExactly) {
  const Scene s = with_views();
  const std::string text = project_file_text(s);
  EXPECT_NE(text.find("\"views\": ["), std::string::npos) << text;
  const Scene loaded = load_project_text(text, "views.glint", s.base_dir, false);
  EXPECT_EQ(loaded.views, s.views);
  EXPECT_EQ(loaded, s);
  EXPECT_EQ(project_file_text(loaded), text);
}

TEST(CameraViewsFile, ViewsAreInNoDigest) {
  const Scene plain = load_project(kProjects / "default.glint");
  const SceneDigests a = digest_scene(plain), b = digest_scene(with_views());
  EXPECT_EQ(a.radiance(), b.radiance());
  EXPECT_EQ(a.display, b.display);
  EXPECT_EQ(a.camera, b.camera);
}

TEST(CameraViewsFile, BadViewsNameTheFileAndTheJsonPath) {
  const Json good = scene_to_json(with_views());
  struct Case {
    const char* what;
    std::function<void(Json&)> edit;
    std::string message;
  };
  const Case cases[] = {
      {"not a list", [](Json& d) { d["views"] = Json::object(); },
       "views.glint: views: expected an array"},
      {"no name", [](Json& d) { d["views"][1].erase("name"); },
       "views.glint: views[1].name: missing required key"},
      {"empty name", [](Json& d) { d["views"][0]["name"] = ""; },
       "views.glint: views[0].name: must not be empty"},
      {"duplicate name", [](Json& d) { d["views"][1]["name"] = "Front"; },
       "views.glint: views[1].name: duplicate view name \"Front\" (first at views[0].name)"},
      {"no camera", [](Json& d) { d["views"][0].erase("camera"); },
       "views.glint: views[0].camera: missing required key"},
      {"unknown key", [](Json& d) { d["views"][0]["zoom"] = 2; },
       "views.glint: views[0].zoom: unknown key"},
      {"unknown camera key", [](Json& d) { d["views"][1]["camera"]["fov"] = 2; },
       "views.glint: views[1].camera.fov: unknown key"},
      {"bad field of view", [](Json& d) { d["views"][1]["camera"]["vfov_deg"] = 180; },
       "views.glint: views[1].camera.vfov_deg: must be in (0, 180) degrees (got 180)"},
      {"up along the view", [](Json& d) { d["views"][1]["camera"]["up"] = Json::array({0, 1, 0}); d["views"][1]["camera"]["target"] = Json::array({0, 0, 0.01}); d["views"][1]["camera"]["position"] = Json::array({0, 8, 0.01}); },
       "views.glint: views[1].camera.up: must not be zero or parallel to the view direction"},
      {"target at the eye", [](Json& d) { d["views"][0]["camera"]["target"] = d["views"][0]["camera"]["position"]; },
       "views.glint: views[0].camera.target: must differ from views[0].camera.position"},
      {"a string for a number", [](Json& d) { d["views"][0]["camera"]["focus_distance"] = "far"; },
       "views.glint: views[0].camera.focus_distance: expected a number"},
  };
  for (const Case& c : cases) {
    Json doc = good;
    c.edit(doc);
    const std::string error = load_error(doc);
    EXPECT_EQ(error.rfind(c.message, 0), 0u) << c.what << ": " << error;
  }
  Json many = good;
  for (size_t i = 0; i <= kMaxCameraViews; ++i) many["views"].push_back(many["views"][0]);
  EXPECT_EQ(load_error(many).rfind("views.glint: views: too many views: 1027 (the limit is 1024)", 0), 0u)
      << load_error(many);
}

}  // namespace
}  // namespace glint
