// Reset semantics by digests: every radiance edit changes the radiance digest; display edits
// change only the display digest (edits as the editor makes them; scene_fields_test.cpp changes
// every field of the tables one at a time).
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "renderer/scene_digest.h"

namespace glint {
namespace {

Scene sample_scene() {
  Scene s;
  s.textures.push_back({.name = "wood", .path = "wood.png"});
  s.materials.push_back({.name = "m", .color_texture = "wood"});
  s.spheres.push_back({.name = "a", .center = {0, 0, 0}, .radius = 1, .material = "m"});
  s.quads.push_back({.name = "q", .material = "m",
                     .corners = {glm::vec3{0, 0, 0}, glm::vec3{0, 1, 0}, glm::vec3{1, 0, 0}, glm::vec3{1, 1, 0}}});
  return s;
}

TEST(SceneDigest, EveryRadianceEditChangesTheRadianceDigestOnly) {
  const std::vector<std::pair<std::string, std::function<void(Scene&)>>> edits = {
      {"sphere centre", [](Scene& s) { s.spheres[0].center.x += 1e-3f; }},
      {"sphere radius", [](Scene& s) { s.spheres[0].radius = 2; }},
      {"sphere material", [](Scene& s) { s.materials.push_back({.name = "n"}); s.spheres[0].material = "n"; }},
      {"quad corner", [](Scene& s) { s.quads[0].corners[3].z = 0.5f; }},
      {"quad uv", [](Scene& s) { s.quads[0].uvs[1] = {0, 2}; }},
      {"material colour", [](Scene& s) { s.materials[0].color.g = 0.1f; }},
      {"material type", [](Scene& s) { s.materials[0].type = MaterialType::glossy; }},
      {"material roughness", [](Scene& s) { s.materials[0].roughness = 0.5f; }},
      {"material ior", [](Scene& s) { s.materials[0].ior = 1.33f; }},
      {"material opacity", [](Scene& s) { s.materials[0].opacity = 0.5f; }},
      {"material emission", [](Scene& s) { s.materials[0].emission = {1, 1, 1}; }},
      {"texture slot", [](Scene& s) { s.materials[0].roughness_texture = "wood"; }},
      {"texture path", [](Scene& s) { s.textures[0].path = "oak.png"; }},
      {"environment colour", [](Scene& s) { s.environment.color = {1, 0, 0}; }},
      {"environment file", [](Scene& s) { s.environment.texture = "sky.hdr"; }},
      {"environment intensity", [](Scene& s) { s.environment.intensity = 2; }},
      {"environment rotation", [](Scene& s) { s.environment.rotation_deg = 90; }},
      {"camera position", [](Scene& s) { s.camera.position.y += 1; }},
      {"camera target", [](Scene& s) { s.camera.target.x += 1; }},
      {"camera up", [](Scene& s) { s.camera.up = {1, 1, 0}; }},
      {"camera fov", [](Scene& s) { s.camera.vfov_deg = 50; }},
      {"camera aperture", [](Scene& s) { s.camera.aperture_radius = 0.1f; }},
      {"camera focus", [](Scene& s) { s.camera.focus_distance = 3; }},
      {"max bounces", [](Scene& s) { s.render.max_bounces = 2; }},
      {"seed", [](Scene& s) { s.render.seed = 1; }},
      {"delete sphere", [](Scene& s) { s.spheres.clear(); }},
      {"add quad", [](Scene& s) { s.quads.push_back(s.quads[0]); }},
  };
  const SceneDigests base = digest_scene(sample_scene());
  for (const auto& [what, edit] : edits) {
    Scene s = sample_scene();
    edit(s);
    SceneDigests d = digest_scene(s);
    EXPECT_NE(d.radiance(), base.radiance()) << what;
    EXPECT_EQ(d.display, base.display) << what;
  }
}

TEST(SceneDigest, DisplayEditsNeverChangeTheRadianceDigest) {
  const SceneDigests base = digest_scene(sample_scene());
  Scene s = sample_scene();
  s.display.exposure = 2;
  EXPECT_EQ(digest_scene(s).radiance(), base.radiance());
  EXPECT_NE(digest_scene(s).display, base.display);
  s.display.tonemap = Tonemap::linear;
  EXPECT_EQ(digest_scene(s).radiance(), base.radiance());
  // Names of objects do not affect radiance either.
  s.spheres[0].name = "renamed";
  EXPECT_EQ(digest_scene(s).radiance(), base.radiance());
}

}  // namespace
}  // namespace glint
