#include <gtest/gtest.h>
#include <stb_image_write.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>

#include "renderer/json_fields.h"
#include "renderer/project_file.h"
#include "renderer/scene_validation.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

using test::TempDir;

void write_text(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary) << text;
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_png(const fs::path& file) {
  fs::create_directories(file.parent_path());
  const unsigned char pixels[2 * 2 * 4] = {255, 0,   0, 255, 0, 255, 0, 255,
                                           0,   0, 255, 255, 9, 9,   9, 128};
  ASSERT_NE(stbi_write_png(file.c_str(), 2, 2, 4, pixels, 2 * 4), 0) << file;
}

void write_hdr(const fs::path& file) {
  fs::create_directories(file.parent_path());
  const float pixels[4 * 2 * 3] = {1, 2, 3, 0.5f, 0.25f, 4, 1, 1, 1, 7, 8, 9,
                                   0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  ASSERT_NE(stbi_write_hdr(file.c_str(), 4, 2, 3, pixels), 0) << file;
}

// Writes the image files that full_scene() refers to into `dir`.
void write_assets(const fs::path& dir) {
  write_png(dir / "assets/wood.png");
  write_png(dir / "assets/rough.png");
  write_hdr(dir / "sky.hdr");
}

// Every field away from its default, with floats that have no short binary form.
Scene full_scene(const fs::path& dir) {
  Scene s;
  s.base_dir = dir;
  s.camera = {{0.1f, 1.25f, -5}, {1 / 3.f, 0.5f, 1e-7f}, {0, 1, 0.2f}, 37.5f, 0.05f, 4.2f};
  s.film = {123, 77};
  s.render = {16, 4000000000u};
  s.display = {-1.3f, Tonemap::linear};
  s.environment = {{0.2f, 0.3f, 0.45f}, "sky.hdr", 2.5f, 123.456f};
  s.textures = {{"wood", "assets/wood.png"}, {"rough", "assets/rough.png"}};
  s.materials = {
      {"floor", MaterialType::matte, {0.8f, 0.7f, 0.6f}, "wood", {}, "", 0.5f, "rough", 1.5f, 1},
      {"lamp", MaterialType::glossy, {.1f, .2f, .3f}, "", {10, 9.5f, 3e5f}, "wood", .25f, "", 1.4f, 1},
      {"metal", MaterialType::reflective, {0.9f, 0.6f, 0.2f}, "", {}, "", 0.01f, "", 1.5f, 1},
      {"glass", MaterialType::transparent, {1, 1, 1}, "wood", {}, "", 0.3f, "", 1.33f, 0.7f},
  };
  s.spheres = {{"ball", {0, 0.5f, 0}, 0.5f, "metal"}, {"", {-1.1f, 2.2f, 3.3f}, 1e-3f, "glass"}};
  s.quads = {{"ground", "floor", {{{-10, 0, -10}, {-10, 0, 10}, {10, 0, -10}, {10, 0, 10}}},
              {{{0, 0}, {0, 5}, {5, 0}, {5, 5}}}},
             {"", "lamp", {{{0, 3, 0}, {0.7f, 3, 0}, {0, 3, 0.7f}, {0.7f, 3, 0.7f}}}, {}}};
  s.quads[1].uvs = Quad{}.uvs;
  return s;
}

void expect_same_scene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.camera.position, b.camera.position);
  EXPECT_EQ(a.camera.target, b.camera.target);
  EXPECT_EQ(a.camera.up, b.camera.up);
  EXPECT_EQ(a.camera.vfov_deg, b.camera.vfov_deg);
  EXPECT_EQ(a.camera.aperture_radius, b.camera.aperture_radius);
  EXPECT_EQ(a.camera.focus_distance, b.camera.focus_distance);
  EXPECT_EQ(a.film.width, b.film.width);
  EXPECT_EQ(a.film.height, b.film.height);
  EXPECT_EQ(a.render.max_bounces, b.render.max_bounces);
  EXPECT_EQ(a.render.seed, b.render.seed);
  EXPECT_EQ(a.display.exposure, b.display.exposure);
  EXPECT_EQ(a.display.tonemap, b.display.tonemap);
  EXPECT_EQ(a.environment.color, b.environment.color);
  EXPECT_EQ(a.environment.texture, b.environment.texture);
  EXPECT_EQ(a.environment.intensity, b.environment.intensity);
  EXPECT_EQ(a.environment.rotation_deg, b.environment.rotation_deg);
  ASSERT_EQ(a.textures.size(), b.textures.size());
  for (size_t i = 0; i < a.textures.size(); ++i) {
    EXPECT_EQ(a.textures[i].name, b.textures[i].name);
    EXPECT_EQ(a.textures[i].path, b.textures[i].path);
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    const Material &x = a.materials[i], &y = b.materials[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.type, y.type);
    EXPECT_EQ(x.color, y.color);
    EXPECT_EQ(x.color_texture, y.color_texture);
    EXPECT_EQ(x.emission, y.emission);
    EXPECT_EQ(x.emission_texture, y.emission_texture);
    EXPECT_EQ(x.roughness, y.roughness);
    EXPECT_EQ(x.roughness_texture, y.roughness_texture);
    EXPECT_EQ(x.ior, y.ior);
    EXPECT_EQ(x.opacity, y.opacity);
  }
  ASSERT_EQ(a.spheres.size(), b.spheres.size());
  for (size_t i = 0; i < a.spheres.size(); ++i) {
    EXPECT_EQ(a.spheres[i].name, b.spheres[i].name);
    EXPECT_EQ(a.spheres[i].center, b.spheres[i].center);
    EXPECT_EQ(a.spheres[i].radius, b.spheres[i].radius);
    EXPECT_EQ(a.spheres[i].material, b.spheres[i].material);
  }
  ASSERT_EQ(a.quads.size(), b.quads.size());
  for (size_t i = 0; i < a.quads.size(); ++i) {
    EXPECT_EQ(a.quads[i].name, b.quads[i].name);
    EXPECT_EQ(a.quads[i].material, b.quads[i].material);
    EXPECT_EQ(a.quads[i].corners, b.quads[i].corners);
    EXPECT_EQ(a.quads[i].uvs, b.quads[i].uvs);
  }
}

// Loads `file`, which must fail; returns the error.
ProjectError load_error(const fs::path& file) {
  try {
    load_project(file);
  } catch (const ProjectError& e) {
    return e;
  }
  ADD_FAILURE() << "loading " << file << " succeeded";
  return ProjectError("", "", "");
}

}  // namespace

TEST(ProjectFile, RoundTripsAFullSceneExactly) {
  TempDir dir;
  write_assets(dir.path());
  const Scene scene = full_scene(dir.path());
  ASSERT_TRUE(validate_scene(scene).empty()) << validate_scene(scene).front().what();

  const fs::path first = dir.path() / "scene.glint", second = dir.path() / "again.glint";
  save_project(scene, first);
  const Scene loaded = load_project(first);
  expect_same_scene(loaded, scene);
  EXPECT_EQ(loaded.base_dir, dir.path());

  save_project(loaded, second);
  EXPECT_EQ(read_text(second), read_text(first));
  EXPECT_EQ(read_text(first), project_file_text(scene));
  const std::string text = read_text(first);
  EXPECT_NE(text.find("\"vfov_deg\": 37.5,"), std::string::npos);
  EXPECT_NE(text.find("\"position\": [0.1, 1.25, -5],"), std::string::npos);
  EXPECT_NE(text.find("\"seed\": 4000000000"), std::string::npos);
}

TEST(ProjectFile, WritesTheCanonicalFormOfTheDesignExample) {
  Scene scene;
  scene.textures = {{"wood", "assets/wood.png"}};
  scene.materials = {{.name = "floor", .color_texture = "wood"}};
  scene.spheres = {{"ball", {0, 0.5f, 0}, 0.5f, "floor"}};
  scene.quads = {{"ground", "floor", {{{-10, 0, -10}, {-10, 0, 10}, {10, 0, -10}, {10, 0, 10}}},
                  {{{0, 0}, {0, 5}, {5, 0}, {5, 5}}}}};
  EXPECT_EQ(project_file_text(scene), R"({
  "format": "glint-project",
  "version": 1,
  "camera": {
    "position": [0, 1, 5],
    "target": [0, 0.5, 0],
    "up": [0, 1, 0],
    "vfov_deg": 40,
    "aperture_radius": 0,
    "focus_distance": 5
  },
  "film": {
    "width": 960,
    "height": 540
  },
  "render": {
    "max_bounces": 8,
    "seed": 0
  },
  "display": {
    "exposure": 0,
    "tonemap": "filmic"
  },
  "environment": {
    "color": [0.5, 0.5, 0.5],
    "texture": null,
    "intensity": 1,
    "rotation_deg": 0
  },
  "textures": [
    {
      "name": "wood",
      "path": "assets/wood.png"
    }
  ],
  "materials": [
    {
      "name": "floor",
      "type": "matte",
      "color": [0.8, 0.8, 0.8],
      "color_texture": "wood",
      "emission": [0, 0, 0],
      "emission_texture": null,
      "roughness": 0,
      "roughness_texture": null,
      "ior": 1.5,
      "opacity": 1
    }
  ],
  "spheres": [
    {
      "name": "ball",
      "center": [0, 0.5, 0],
      "radius": 0.5,
      "material": "floor"
    }
  ],
  "quads": [
    {
      "name": "ground",
      "material": "floor",
      "corners": [[-10, 0, -10], [-10, 0, 10], [10, 0, -10], [10, 0, 10]],
      "uvs": [[0, 0], [0, 5], [5, 0], [5, 5]]
    }
  ]
}
)");
}

TEST(ProjectFile, FloatsRoundTripThroughTheirShortestText) {
  EXPECT_EQ(json_fields::float_to_json(0.1f).dump(), "0.1");
  EXPECT_EQ(json_fields::float_to_json(40.0f).dump(), "40");
  EXPECT_EQ(json_fields::float_to_json(-0.0f).dump(), "-0.0");
  EXPECT_EQ(json_fields::float_to_json(1e15f).dump(), "1e+15");  // not 999999986991104
  // 7.038531e-26f is the one positive float whose shortest text, read as a double, rounds to
  // a different float.
  std::vector<float> values = {7.038531e-26f, -7.038531e-26f, 0.1f, 1 / 3.f, 1e-7f, 123456.79f,
                               16777216.f, 1e20f, -2.5f,
                               std::numeric_limits<float>::max(), std::numeric_limits<float>::min(),
                               std::numeric_limits<float>::denorm_min(), -0.0f};
  std::mt19937 random(12345);
  while (values.size() < 100000) {
    const uint32_t bits = random();
    float f;
    std::memcpy(&f, &bits, sizeof f);
    if (std::isfinite(f)) values.push_back(f);
  }
  for (float f : values) {
    const Json parsed = Json::parse(json_fields::float_to_json(f).dump());
    const float back = json_fields::read_float(parsed, "test", "x");
    ASSERT_EQ(std::memcmp(&back, &f, sizeof f), 0) << json_fields::float_text(f);
  }
}

TEST(ProjectFile, MissingKeysTakeTheDefaults) {
  TempDir dir;
  const fs::path file = dir.path() / "minimal.glint";
  write_text(file, R"({"format": "glint-project", "version": 1})");
  expect_same_scene(load_project(file), Scene{});

  write_text(file, R"({"format": "glint-project", "version": 1, "camera": {"vfov_deg": 30},
    "materials": [{"name": "m"}],
    "spheres": [{"center": [1, 2, 3], "radius": 2, "material": "m"}],
    "quads": [{"material": "m", "corners": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]}]})");
  const Scene scene = load_project(file);
  EXPECT_EQ(scene.camera.vfov_deg, 30);
  EXPECT_EQ(scene.camera.position, Camera{}.position);
  EXPECT_EQ(scene.camera.focus_distance, Camera{}.focus_distance);
  Material expected_material;
  expected_material.name = "m";
  Scene expected;
  expected.camera.vfov_deg = 30;
  expected.materials = {expected_material};
  expected.spheres = {{"", {1, 2, 3}, 2, "m"}};
  expected.quads = {{"", "m", {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}}}};
  expect_same_scene(scene, expected);
}

// One bad value at a time, set into the JSON of a valid full scene.
struct BadValue {
  const char* pointer;  // JSON pointer of the value to replace ("" is the whole document)
  Json value;           // the bad value; kErase removes the key instead
  const char* path;     // the expected JSON path, exactly
  const char* problem;  // a part of the expected problem
};
const Json kErase(Json::value_t::discarded);

TEST(ProjectFile, ReportsEachProblemWithFileAndJsonPath) {
  TempDir dir;
  write_assets(dir.path());
  write_text(dir.path() / "notes.txt", "not an image");
  const Json valid = scene_to_json(full_scene(dir.path()));
  const Json line = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  const Json p3_is_p1 = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}};
  const Json one_point = {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}};
  const Json looking_down_up = {{"position", {0, 0, 5}}, {"target", {0, 0, 0}}, {"up", {0, 0, -2}}};
  const std::vector<BadValue> cases = {
      // Structure: unknown keys, types, required keys, format and version.
      {"/colour", 1, "colour", "unknown key"},
      {"/camera/fov", 1, "camera.fov", "unknown key (expected one of: position, target,"},
      {"/spheres/0/raduis", 1, "spheres[0].raduis", "unknown key"},
      {"/materials/1/colour", 1, "materials[1].colour", "unknown key"},
      {"", Json::array(), "", "expected a JSON object, got an array"},
      {"/format", "gltf", "format", "expected \"glint-project\""},
      {"/format", kErase, "format", "missing"},
      {"/version", 2, "version", "unsupported version 2"},
      {"/version", kErase, "version", "missing"},
      {"/camera", 5, "camera", "expected an object, got number 5"},
      {"/spheres", Json::object(), "spheres", "expected an array"},
      {"/materials/0", "floor", "materials[0]", "expected an object"},
      {"/spheres/0/radius", "big", "spheres[0].radius", "expected a number, got string \"big\""},
      {"/camera/position/1", "x", "camera.position[1]", "expected a number"},
      {"/camera/position", {0, 1}, "camera.position", "expected an array of 3 numbers"},
      {"/quads/0/corners/3", kErase, "quads[0].corners", "expected an array of 4 points"},
      {"/quads/0/uvs/2", {0}, "quads[0].uvs[2]", "expected an array of 2 numbers"},
      {"/textures/0/name", 5, "textures[0].name", "expected a string"},
      {"/materials/0/color_texture", "", "materials[0].color_texture", "use null for none"},
      {"/environment/texture", false, "environment.texture", "expected a string or null"},
      {"/materials/0/name", kErase, "materials[0].name", "missing required key"},
      {"/spheres/0/center", kErase, "spheres[0].center", "missing required key"},
      {"/spheres/0/radius", kErase, "spheres[0].radius", "missing required key"},
      {"/spheres/1/material", kErase, "spheres[1].material", "missing required key"},
      {"/quads/0/corners", kErase, "quads[0].corners", "missing required key"},
      {"/quads/1/material", kErase, "quads[1].material", "missing required key"},
      {"/textures/1/path", kErase, "textures[1].path", "missing required key"},
      // Numbers.
      {"/spheres/1/center/2", 1e39, "spheres[1].center[2]", "out of range of a 32-bit float"},
      {"/spheres/0/radius", 0, "spheres[0].radius", "must be greater than 0 (got 0)"},
      {"/spheres/1/radius", -1, "spheres[1].radius", "must be greater than 0 (got -1)"},
      {"/quads/0/corners", line, "quads[0].corners", "zero-area quad"},
      {"/quads/0/corners", p3_is_p1, "quads[0].corners", "triangle p1, p3, p2 is degenerate"},
      {"/quads/1/corners", one_point, "quads[1].corners", "zero-area quad"},
      {"/film/width", 0, "film.width", "must be an integer in [1, 16384] (got 0)"},
      {"/film/height", 16385, "film.height", "must be an integer in [1, 16384] (got 16385)"},
      {"/film/width", 1.5, "film.width", "expected an integer, got number 1.5"},
      {"/render/max_bounces", -1, "render.max_bounces", "in [0, 1024] (got -1)"},
      {"/render/max_bounces", 1025, "render.max_bounces", "in [0, 1024] (got 1025)"},
      {"/render/seed", -1, "render.seed", "in [0, 4294967295] (got -1)"},
      {"/render/seed", 4294967296u, "render.seed", "(got 4294967296)"},
      {"/render/seed", 2.5, "render.seed", "expected an integer"},
      {"/camera/vfov_deg", 0, "camera.vfov_deg", "must be in (0, 180)"},
      {"/camera/vfov_deg", 180, "camera.vfov_deg", "must be in (0, 180)"},
      {"/camera/aperture_radius", -0.1, "camera.aperture_radius", "must be at least 0"},
      {"/camera/focus_distance", 0, "camera.focus_distance", "must be greater than 0"},
      {"/camera/target", valid["camera"]["position"], "camera.target", "must differ from"},
      {"/camera", looking_down_up, "camera.up", "parallel to the view direction"},
      {"/camera/up", {0, 0, 0}, "camera.up", "must not be zero"},
      {"/environment/intensity", -1, "environment.intensity", "must be at least 0"},
      {"/environment/color/1", -0.5, "environment.color[1]", "must be at least 0"},
      {"/materials/0/color/2", -1, "materials[0].color[2]", "must be at least 0"},
      {"/materials/1/emission/0", -1, "materials[1].emission[0]", "must be at least 0"},
      {"/materials/0/roughness", 1.5, "materials[0].roughness", "must be in [0, 1] (got 1.5)"},
      {"/materials/2/roughness", -0.1, "materials[2].roughness", "must be in [0, 1] (got -0.1)"},
      {"/materials/0/ior", 0, "materials[0].ior", "must be greater than 0 (got 0)"},
      {"/materials/3/opacity", 1.1, "materials[3].opacity", "must be in [0, 1] (got 1.1)"},
      {"/materials/3/opacity", -0.1, "materials[3].opacity", "must be in [0, 1]"},
      // Names and references.
      {"/materials/0/type", "metal", "materials[0].type", "unknown material type \"metal\""},
      {"/display/tonemap", "aces", "display.tonemap", "unknown tonemap \"aces\""},
      {"/materials/0/name", "", "materials[0].name", "must not be empty"},
      {"/materials/2/name", "floor", "materials[2].name",
       "duplicate material name \"floor\" (first at materials[0].name)"},
      {"/textures/1/name", "wood", "textures[1].name", "duplicate texture name \"wood\""},
      {"/spheres/0/material", "nope", "spheres[0].material", "unknown material \"nope\""},
      {"/quads/1/material", "nope", "quads[1].material", "unknown material \"nope\""},
      {"/materials/0/color_texture", "oak", "materials[0].color_texture", "unknown texture \"oak"},
      {"/materials/1/emission_texture", "oak", "materials[1].emission_texture", "unknown texture"},
      {"/materials/0/roughness_texture", "oak", "materials[0].roughness_texture", "unknown tex"},
      // Image files.
      {"/textures/0/path", "assets/missing.png", "textures[0].path", "cannot read image"},
      {"/textures/1/path", "notes.txt", "textures[1].path", "cannot read image"},
      {"/textures/1/path", "", "textures[1].path", "must not be empty"},
      {"/environment/texture", "missing.hdr", "environment.texture", "cannot read image"},
  };
  const fs::path file = dir.path() / "bad.glint";
  write_text(file, valid.dump(2));
  ASSERT_NO_THROW(load_project(file));  // so each case fails for its own reason only
  for (const BadValue& c : cases) {
    SCOPED_TRACE(std::string(c.pointer) + " -> " + c.path + ": " + c.problem);
    Json doc = valid;
    const Json::json_pointer pointer(c.pointer);
    Json& parent = doc[pointer.parent_pointer()];
    if (!c.value.is_discarded())
      doc[pointer] = c.value;
    else if (parent.is_array())
      parent.erase(std::stoul(pointer.back()));
    else
      parent.erase(pointer.back());
    write_text(file, doc.dump(2));
    const ProjectError e = load_error(file);
    EXPECT_EQ(e.file, file.string());
    EXPECT_EQ(e.json_path, c.path);
    EXPECT_NE(e.problem.find(c.problem), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()),
              file.string() + ": " + (e.json_path.empty() ? "" : e.json_path + ": ") + e.problem);
  }
}

TEST(ProjectFile, ErrorMessageReadsFilePathProblem) {
  TempDir dir;
  const fs::path file = dir.path() / "a.glint";
  write_text(file, R"({"format": "glint-project", "version": 1, "materials": [{"name": "m"}],
    "spheres": [{"center": [0, 0, 0], "radius": -1, "material": "m"}]})");
  EXPECT_STREQ(load_error(file).what(),
               (file.string() + ": spheres[0].radius: must be greater than 0 (got -1)").c_str());
}

TEST(ProjectFile, ReportsBadJsonTextWithItsPosition) {
  TempDir dir;
  const fs::path file = dir.path() / "broken.glint";
  write_text(file, "{\n  \"format\": \"glint-project\",\n  \"version\": 1,\n"
                   "  \"camera\": {\"vfov_deg\": 4");
  ProjectError e = load_error(file);
  EXPECT_EQ(e.json_path, "");
  EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  EXPECT_NE(e.problem.find("invalid JSON: parse error at line 4, column"), std::string::npos)
      << e.what();

  write_text(file, "");
  EXPECT_NE(load_error(file).problem.find("invalid JSON"), std::string::npos);

  // nlohmann would silently keep the last of two equal keys; a project must not.
  write_text(file, R"({"format": "glint-project", "version": 1, "materials": [{"name": "m"}],
    "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "m"},
                {"center": [0, 0, 0], "radius": 1, "radius": 2, "material": "m"}]})");
  e = load_error(file);
  EXPECT_EQ(e.json_path, "spheres[1].radius");
  EXPECT_EQ(e.problem, "duplicate key");

  e = load_error(dir.path() / "missing.glint");
  EXPECT_EQ(e.file, (dir.path() / "missing.glint").string());
  EXPECT_EQ(e.problem, "no such file");
  EXPECT_FALSE(load_error(dir.path()).problem.empty());  // a folder
}

TEST(ProjectFile, SavesAtomicallyWithoutLeavingATemporaryFile) {
  TempDir dir;
  write_assets(dir.path());
  Scene scene = full_scene(dir.path());
  const fs::path file = dir.path() / "scene.glint";
  save_project(scene, file);
  scene.film.width = 64;
  save_project(scene, file);  // over the old one
  EXPECT_EQ(load_project(file).film.width, 64);
  EXPECT_FALSE(fs::exists(dir.path() / "scene.glint.tmp"));
  for (const auto& entry : fs::directory_iterator(dir.path()))
    EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();
  const std::string text = read_text(file);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  EXPECT_EQ(text.rfind("{\n  \"format\": \"glint-project\",\n  \"version\": 1,\n", 0), 0u);
}

TEST(ProjectFile, FailedSaveNamesTheFileAndLeavesNothingBehind) {
  TempDir dir;
  const Scene scene;
  const fs::path missing_folder = dir.path() / "no/such/folder/scene.glint";
  try {
    save_project(scene, missing_folder);
    ADD_FAILURE() << "saving into a missing folder succeeded";
  } catch (const ProjectError& e) {
    EXPECT_NE(std::string(e.what()).find(missing_folder.string()), std::string::npos) << e.what();
  }
  // The target is a non-empty folder: the rename fails after the temporary file was written.
  const fs::path blocked = dir.path() / "blocked.glint";
  write_text(blocked / "keep.txt", "x");
  EXPECT_THROW(save_project(scene, blocked), ProjectError);
  EXPECT_FALSE(fs::exists(dir.path() / "blocked.glint.tmp"));
  EXPECT_TRUE(fs::exists(blocked / "keep.txt"));
}

TEST(ProjectFile, SaveAsRewritesRelativeAssetPaths) {
  TempDir dir;
  const fs::path old_dir = dir.path() / "a", new_dir = dir.path() / "b/sub";
  write_assets(old_dir);
  write_png(dir.path() / "absolute.png");
  Scene scene = full_scene(old_dir);
  scene.textures.push_back({"abs", (dir.path() / "absolute.png").string()});
  save_project(scene, old_dir / "scene.glint");
  const Scene loaded = load_project(old_dir / "scene.glint");

  fs::create_directories(new_dir);
  save_project(loaded, new_dir / "copy.glint");
  const Json doc = Json::parse(read_text(new_dir / "copy.glint"));
  EXPECT_EQ(doc["textures"][0]["path"], "../../a/assets/wood.png");
  EXPECT_EQ(doc["textures"][2]["path"], "../../absolute.png");  // was absolute: now relative too
  EXPECT_EQ(doc["environment"]["texture"], "../../a/sky.hdr");

  const Scene copy = load_project(new_dir / "copy.glint");  // the files are still found
  for (size_t i = 0; i < copy.textures.size(); ++i)
    EXPECT_TRUE(fs::equivalent(resolve_asset_path(copy, copy.textures[i].path),
                               resolve_asset_path(scene, scene.textures[i].path)));
  EXPECT_TRUE(fs::equivalent(resolve_asset_path(copy, copy.environment.texture),
                             old_dir / "sky.hdr"));

  // The editor's view of the same: the document rebased onto the new folder.
  const Scene rebased = rebase_asset_paths(loaded, new_dir);
  EXPECT_EQ(rebased.base_dir, new_dir);
  EXPECT_EQ(rebased.textures[1].path, "../../a/assets/rough.png");

  // Saving into the same folder (spelled differently) keeps paths exactly as written.
  scene.textures[0].path = "./assets/../assets/wood.png";
  fs::create_directories(old_dir / "sub");
  save_project(scene, old_dir / "sub/../same.glint");
  EXPECT_EQ(load_project(old_dir / "same.glint").textures[0].path, "./assets/../assets/wood.png");
}

// Absolute asset paths are written relative to the project file, `../` included, so that a
// project moved together with its assets keeps working; the loader resolves them against the
// project's folder (not the current one). `../` climbs from the folder as the system resolves it
// (through a symbolic link to the folder) and from a `..` inside an absolute path.
TEST(ProjectFile, SavesAbsoluteAssetPathsRelativeToTheProject) {
  TempDir dir;
  const fs::path work = dir.path() / "work";
  write_png(work / "shared/textures/t.png");
  write_hdr(work / "project/hdr/sky.hdr");
  Scene scene = full_scene(work / "project");
  scene.textures = {{"wood", (work / "shared/textures/t.png").string()},
                    {"rough", (work / "project/hdr/../../shared/textures/t.png").string()}};
  scene.environment.texture = (work / "project/hdr/sky.hdr").string();
  save_project(scene, work / "project/scene.glint");
  const Json doc = Json::parse(read_text(work / "project/scene.glint"));
  EXPECT_EQ(doc["textures"][0]["path"], "../shared/textures/t.png");
  EXPECT_EQ(doc["textures"][1]["path"], "../shared/textures/t.png");
  EXPECT_EQ(doc["environment"]["texture"], "hdr/sky.hdr");

  // Moved elsewhere as a whole: everything is found at its new place.
  const fs::path moved = dir.path() / "elsewhere/deeper";
  fs::create_directories(moved.parent_path());
  fs::rename(work, moved);
  const Scene loaded = load_project(moved / "project/scene.glint");
  EXPECT_TRUE(fs::equivalent(resolve_asset_path(loaded, loaded.textures[0].path), moved / "shared/textures/t.png"));
  EXPECT_TRUE(fs::equivalent(resolve_asset_path(loaded, loaded.environment.texture), moved / "project/hdr/sky.hdr"));

  // Saved through a link to its folder: `../` leaves the real folder, as the system does.
  fs::create_directories(dir.path() / "links");
  fs::create_directory_symlink(moved / "project", dir.path() / "links/project");
  Scene linked = load_project(moved / "project/scene.glint");
  linked.textures[0].path = (moved / "shared/textures/t.png").string();
  save_project(linked, dir.path() / "links/project/via_link.glint");
  const Scene via_link = load_project(dir.path() / "links/project/via_link.glint");  // throws if unresolved
  EXPECT_EQ(via_link.textures[0].path, "../shared/textures/t.png");
  EXPECT_TRUE(fs::equivalent(resolve_asset_path(via_link, via_link.textures[0].path), moved / "shared/textures/t.png"));
}

// The in-memory pair (the fuzz target's round trip): save_project_text is byte for byte what
// save_project writes, rebased the same way, and writes nothing; load_project_text reads it back.
TEST(ProjectFile, SavesAndLoadsInMemoryAsThroughFiles) {
  TempDir dir;
  const fs::path old_dir = dir.path() / "a", new_dir = dir.path() / "b";
  write_assets(old_dir);
  fs::create_directories(new_dir);
  const Scene scene = full_scene(old_dir);
  EXPECT_EQ(save_project_text(scene, old_dir / "scene.glint"), project_file_text(scene));
  const std::string text = save_project_text(scene, new_dir / "copy.glint");
  EXPECT_FALSE(fs::exists(new_dir / "copy.glint"));
  EXPECT_TRUE(fs::is_empty(new_dir));
  save_project(scene, new_dir / "copy.glint");
  EXPECT_EQ(read_text(new_dir / "copy.glint"), text);
  EXPECT_NE(text.find("\"../a/assets/wood.png\""), std::string::npos);
  const Scene from_text = load_project_text(text, "copy.glint", new_dir);
  expect_same_scene(from_text, load_project(new_dir / "copy.glint"));
  EXPECT_EQ(from_text.base_dir, new_dir);

  // A name that JSON text cannot hold fails in memory as it does when saving, naming the file.
  Scene bad = scene;
  bad.spheres[0].name = "\xff";
  try {
    (void)save_project_text(bad, new_dir / "bad.glint");
    ADD_FAILURE() << "invalid UTF-8 was saved";
  } catch (const ProjectError& e) {
    EXPECT_EQ(e.file, (new_dir / "bad.glint").string());
    EXPECT_EQ(e.json_path, "spheres[0].name");
  }
  EXPECT_FALSE(fs::exists(new_dir / "bad.glint"));
}

TEST(ProjectFile, ValidatesScenesEditedThroughTheApi) {
  Scene scene;
  EXPECT_TRUE(validate_scene(scene).empty());
  scene.materials = {{.name = "m"}};
  scene.spheres = {{"", {std::nanf(""), 0, 0}, -1, "m"}, {"", {0, 0, 0}, 1, "gone"}};
  scene.film.height = 0;
  const auto problems = validate_scene(scene);
  ASSERT_EQ(problems.size(), 4u);
  EXPECT_STREQ(problems[0].what(), "film.height: must be an integer in [1, 16384] (got 0)");
  EXPECT_STREQ(problems[1].what(), "spheres[0].center[0]: must be a finite number (got nan)");
  EXPECT_STREQ(problems[2].what(), "spheres[0].radius: must be greater than 0 (got -1)");
  EXPECT_STREQ(problems[3].what(), "spheres[1].material: unknown material \"gone\"");
  for (const ProjectError& e : problems) EXPECT_EQ(e.file, "");

  // Files are checked only when asked.
  Scene textured;
  textured.base_dir = "/nonexistent/folder";
  textured.textures = {{"t", "t.png"}};
  EXPECT_TRUE(validate_scene(textured, false).empty());
  ASSERT_EQ(validate_scene(textured, true).size(), 1u);
  EXPECT_EQ(validate_scene(textured, true)[0].json_path, "textures[0].path");
}

}  // namespace glint
