// Scene exchange (renderer/scene_exchange.h): every example project survives Glint -> Mitsuba
// -> Glint and Glint -> pbrt -> Glint field by field, except what the writers name in a warning
// (expected_round_trip lists those losses), and the warnings themselves.
#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "renderer/mitsuba_scene.h"
#include "renderer/pbrt_scene.h"
#include "renderer/project_file.h"
#include "renderer/scene_exchange.h"
#include "renderer/xml_reader.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> example_projects() {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(fs::path(GLINT_SOURCE_DIR) / "projects"))
    if (e.path().extension() == ".glint") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

bool has_colour_texture_user(const Scene& s, const std::string& texture) {
  for (const Material& m : s.materials)
    if (m.color_texture == texture) return true;
  return false;
}

// The scene a round trip through `format` gives back: the original less what the writer warns
// it does not write, and the forms the reader chooses for what renders alike.
Scene expected_round_trip(Scene s, SceneFormat format) {
  s.display = {};
  if (s.camera.aperture_radius == 0) s.camera.focus_distance = glm::length(s.camera.target - s.camera.position);
  for (Material& m : s.materials) {
    m.roughness_texture.clear();
    m.emission_texture.clear();
    if (m.type == MaterialType::transparent) m.roughness = 0;
    if (format == SceneFormat::mitsuba && m.type == MaterialType::refractive && m.roughness < 0.03f) m.roughness = 0;
    if (format == SceneFormat::pbrt && (m.type == MaterialType::transparent || m.type == MaterialType::refractive)) {
      m.color = glm::vec3(1);
      m.color_texture.clear();
    }
  }
  std::erase_if(s.textures, [&](const Texture& t) { return !has_colour_texture_user(s, t.name); });
  if (format == SceneFormat::mitsuba) {  // Mitsuba's ids are unique: a repeated name is not written
    std::set<std::string> ids;
    for (const Material& m : s.materials) ids.insert(m.name);
    for (Sphere& x : s.spheres)
      if (!ids.insert(x.name).second) x.name.clear();
    for (Quad& x : s.quads)
      if (!ids.insert(x.name).second) x.name.clear();
  }
  Environment& env = s.environment;
  if (!env.texture.empty() && format == SceneFormat::mitsuba) {
    env.color = glm::vec3(1);
  } else {
    env = Environment{env.color * env.intensity, "", 1, 0};
  }
  return s;
}

// Differences between two scenes, field by field; floats agree within 1e-5 of their size.
class SceneDiff {
 public:
  std::vector<std::string> out;
  void f(const std::string& path, float a, float b) {
    if (std::abs(a - b) > 1e-5f * std::max({1.0f, std::abs(a), std::abs(b)}))
      out.push_back(path + ": " + std::to_string(a) + " != " + std::to_string(b));
  }
  template <int N>
  void v(const std::string& path, glm::vec<N, float> a, glm::vec<N, float> b) {
    for (int k = 0; k < N; ++k) f(path + "[" + std::to_string(k) + "]", a[k], b[k]);
  }
  template <class T>
  void eq(const std::string& path, const T& a, const T& b) {
    if (!(a == b)) out.push_back(path + " differs");
  }
  void scenes(const Scene& a, const Scene& b) {
    v<3>("camera.position", a.camera.position, b.camera.position);
    v<3>("camera.target", a.camera.target, b.camera.target);
    v<3>("camera.up", a.camera.up, b.camera.up);
    f("camera.vfov_deg", a.camera.vfov_deg, b.camera.vfov_deg);
    f("camera.aperture_radius", a.camera.aperture_radius, b.camera.aperture_radius);
    f("camera.focus_distance", a.camera.focus_distance, b.camera.focus_distance);
    eq("film", a.film, b.film);
    eq("render", a.render, b.render);
    eq("display", a.display, b.display);
    v<3>("environment.color", a.environment.color, b.environment.color);
    eq("environment.texture", a.environment.texture, b.environment.texture);
    f("environment.intensity", a.environment.intensity, b.environment.intensity);
    f("environment.rotation_deg", a.environment.rotation_deg, b.environment.rotation_deg);
    auto by_name = [](std::vector<Texture> t) {  // readers add textures in the order materials use them
      std::sort(t.begin(), t.end(), [](const Texture& x, const Texture& y) { return x.name < y.name; });
      return t;
    };
    eq("textures", by_name(a.textures), by_name(b.textures));
    eq("materials.size", a.materials.size(), b.materials.size());
    for (size_t i = 0; i < std::min(a.materials.size(), b.materials.size()); ++i) {
      const Material &x = a.materials[i], &y = b.materials[i];
      const std::string p = "materials[" + std::to_string(i) + "] (" + x.name + ")";
      eq(p + ".name", x.name, y.name);
      eq(p + ".type", x.type, y.type);
      v<3>(p + ".color", x.color, y.color);
      eq(p + ".color_texture", x.color_texture, y.color_texture);
      v<3>(p + ".emission", x.emission, y.emission);
      eq(p + ".emission_texture", x.emission_texture, y.emission_texture);
      f(p + ".roughness", x.roughness, y.roughness);
      eq(p + ".roughness_texture", x.roughness_texture, y.roughness_texture);
      f(p + ".ior", x.ior, y.ior);
      f(p + ".opacity", x.opacity, y.opacity);
    }
    eq("spheres.size", a.spheres.size(), b.spheres.size());
    for (size_t i = 0; i < std::min(a.spheres.size(), b.spheres.size()); ++i) {
      const std::string p = "spheres[" + std::to_string(i) + "]";
      eq(p + ".name", a.spheres[i].name, b.spheres[i].name);
      eq(p + ".material", a.spheres[i].material, b.spheres[i].material);
      v<3>(p + ".center", a.spheres[i].center, b.spheres[i].center);
      f(p + ".radius", a.spheres[i].radius, b.spheres[i].radius);
    }
    eq("quads.size", a.quads.size(), b.quads.size());
    for (size_t i = 0; i < std::min(a.quads.size(), b.quads.size()); ++i) {
      const std::string p = "quads[" + std::to_string(i) + "]";
      eq(p + ".name", a.quads[i].name, b.quads[i].name);
      eq(p + ".material", a.quads[i].material, b.quads[i].material);
      for (int k = 0; k < 4; ++k) {
        v<3>(p + ".corners[" + std::to_string(k) + "]", a.quads[i].corners[k], b.quads[i].corners[k]);
        v<2>(p + ".uvs[" + std::to_string(k) + "]", a.quads[i].uvs[k], b.quads[i].uvs[k]);
      }
    }
    eq("base_dir", a.base_dir, b.base_dir);
  }
};

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += "  " + l + "\n";
  return out;
}

void check_round_trip(const fs::path& project, const char* extension, SceneFormat format) {
  test::TempDir dir;
  const Scene original = load_project(project);
  const fs::path file = dir / (project.stem().string() + extension);
  const std::vector<std::string> written = export_scene(original, file);
  const ImportedScene back = import_scene(file);
  SceneDiff diff;
  diff.scenes(expected_round_trip(rebase_asset_paths(original, dir.path()), format), back.scene);
  EXPECT_TRUE(diff.out.empty()) << project.filename() << " through " << extension << ":\n" << joined(diff.out)
                                << "export warnings:\n" << joined(written) << "import warnings:\n" << joined(back.warnings);
}

TEST(SceneExchange, EveryExampleProjectRoundTripsThroughMitsuba) {
  for (const fs::path& p : example_projects()) check_round_trip(p, ".xml", SceneFormat::mitsuba);
}

TEST(SceneExchange, EveryExampleProjectRoundTripsThroughPbrt) {
  for (const fs::path& p : example_projects()) check_round_trip(p, ".pbrt", SceneFormat::pbrt);
}

TEST(SceneExchange, GlintToGlintIsTheProjectFile) {
  test::TempDir dir;
  const Scene original = load_project(fs::path(GLINT_SOURCE_DIR) / "projects/cornell_box.glint");
  EXPECT_TRUE(export_scene(original, dir / "copy.glint").empty());
  const ImportedScene back = import_scene(dir / "copy.glint");
  EXPECT_TRUE(back.warnings.empty());
  EXPECT_EQ(back.scene, rebase_asset_paths(original, dir.path()));
}

TEST(SceneExchange, FormatsFollowTheExtension) {
  EXPECT_EQ(scene_format_for("a/b.GLINT"), SceneFormat::glint);
  EXPECT_EQ(scene_format_for("scene.xml"), SceneFormat::mitsuba);
  EXPECT_EQ(scene_format_for("scene.pbrt"), SceneFormat::pbrt);
  EXPECT_FALSE(scene_format_for("scene.obj"));
  EXPECT_FALSE(scene_format_for("scene"));
}

bool any_contains(const std::vector<std::string>& lines, const std::string& part) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(part) != std::string::npos; });
}

// A scene with one of each thing that does not map.
Scene unmappable_scene() {
  Scene s = load_project(fs::path(GLINT_SOURCE_DIR) / "projects/default.glint");
  s.display.exposure = 1;
  Material thin{"frosted", MaterialType::transparent, glm::vec3(0.9f, 1, 0.9f)};
  thin.roughness = 0.2f;
  s.materials.push_back(thin);
  return s;
}

TEST(SceneExchange, MitsubaWriterNamesWhatItDoesNotWrite) {
  const ExportedScene out = write_mitsuba_scene(unmappable_scene(), "x", {});
  const auto& w = out.warnings;
  EXPECT_TRUE(any_contains(w, "display: exposure and tone curve are not written")) << joined(w);
  EXPECT_TRUE(any_contains(w, "material \"wood_floor\": its roughness texture is not written")) << joined(w);
  EXPECT_TRUE(any_contains(w, "material \"red_glossy\": glossy is written as Mitsuba's roughplastic")) << joined(w);
  EXPECT_TRUE(any_contains(w, "material \"frosted\": the roughness of thin glass (0.2) is not written")) << joined(w);
  EXPECT_TRUE(any_contains(w, "material \"mirror\": a coloured mirror")) << joined(w);
  EXPECT_TRUE(any_contains(w, "environment: Mitsuba's envmap puts the image's first and last rows on the poles")) << joined(w);
  EXPECT_FALSE(any_contains(w, "\"cutout\"")) << "a white matte with a colour texture maps exactly\n" << joined(w);
}

TEST(SceneExchange, PbrtWriterNamesWhatItDoesNotWrite) {
  const ExportedScene out = write_pbrt_scene(unmappable_scene(), "x", {});
  const auto& w = out.warnings;
  EXPECT_TRUE(any_contains(w, "display: exposure and tone curve are not written")) << joined(w);
  EXPECT_TRUE(any_contains(w, "environment: its lat-long image \"assets/sky.hdr\" is not written")) << joined(w);
  EXPECT_TRUE(any_contains(w, "material \"frosted\": the tint of thin glass is not written")) << joined(w);
  EXPECT_TRUE(any_contains(w, "material \"frosted\": the roughness of thin glass is not written")) << joined(w);
  EXPECT_TRUE(any_contains(w, "material \"brushed_metal\": its roughness texture is not written")) << joined(w);
}

TEST(SceneExchange, MitsubaWriterMakesEmissiveQuadsTwoSided) {
  const Scene s = load_project(fs::path(GLINT_SOURCE_DIR) / "projects/cornell_box.glint");
  const ExportedScene out = write_mitsuba_scene(s, "box", {});
  EXPECT_NE(out.text.find("id=\"glint-back-of-quad-"), std::string::npos);
  ASSERT_EQ(out.side_files.size(), 1u);  // the light's back copy; the walls are rectangles
  EXPECT_EQ(out.side_files[0].relative_path.rfind("box-meshes/quad-", 0), 0u);
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// Mitsuba's twosided refuses a BSDF that transmits ("Only materials without a transmission
// component can be nested"): glass must not be wrapped, or Mitsuba cannot load the file.
bool twosided_wraps_glass(const XmlElement& e) {
  if (e.name == "bsdf" && e.attribute("type") && *e.attribute("type") == "twosided")
    for (const XmlElement& c : e.children)
      if (c.name == "bsdf" && c.attribute("type") && c.attribute("type")->find("dielectric") != std::string::npos) return true;
  for (const XmlElement& c : e.children)
    if (twosided_wraps_glass(c)) return true;
  return false;
}

TEST(SceneExchange, MitsubaWriterNeverWrapsGlassInTwosided) {
  for (const fs::path& p : example_projects()) {
    const ExportedScene out = write_mitsuba_scene(load_project(p), "x", {});
    EXPECT_FALSE(twosided_wraps_glass(parse_xml(out.text, p.string()))) << p.filename();
  }
}

}  // namespace
}  // namespace glint
