// Every field of every table (renderer/scene_fields.h), changed one at a time through the same
// table: the digests change as scene_digest.h says (radiance fields restart the accumulation,
// display fields only re-run the tonemap, labels and the film change no digest), and the
// project file writes the change and reads it back exactly.
#include <fstream>
#include <string>
#include <type_traits>
#include <vector>

#include <gtest/gtest.h>

#include "renderer/project_file.h"
#include "renderer/scene_digest.h"
#include "renderer/scene_fields.h"
#include "renderer/scene_validation.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

// Two of each list, so that every reference has another valid target.
Scene sample_scene() {
  Scene s;
  s.textures = {{.name = "wood", .path = "wood.png"}, {.name = "oak", .path = "oak.png"}};
  s.materials = {{.name = "m", .color_texture = "wood"}, {.name = "n"}};
  s.spheres = {{.name = "a", .center = {0, 0, 0}, .radius = 1, .material = "m"}};
  s.quads = {{.name = "q", .material = "m",
              .corners = {glm::vec3{0, 0, 0}, glm::vec3{0, 1, 0}, glm::vec3{1, 0, 0}, glm::vec3{1, 1, 0}}}};
  s.views = {{.name = "front", .camera = {}}, {.name = "side", .camera = {.position = {5, 1, 0}}}};
  return s;
}

// The digest that a change of the part under `key` must change, as scene_digest.h documents
// it; nullptr for the film (the renderer compares its size itself) and the camera views
// (bookmarks: in no digest, so saving, renaming or deleting one never restarts the render).
uint64_t SceneDigests::*digest_of_part(const std::string& key) {
  if (key == "camera") return &SceneDigests::camera;
  if (key == "render") return &SceneDigests::settings;
  if (key == "display") return &SceneDigests::display;
  if (key == "environment") return &SceneDigests::environment;
  if (key == "textures") return &SceneDigests::textures;
  if (key == "materials") return &SceneDigests::materials;
  if (key == "spheres" || key == "quads") return &SceneDigests::geometry;
  return nullptr;
}

constexpr uint64_t SceneDigests::*kAllDigests[] = {
    &SceneDigests::geometry, &SceneDigests::materials, &SceneDigests::textures,
    &SceneDigests::environment, &SceneDigests::camera, &SceneDigests::settings,
    &SceneDigests::display};

// Other values for a field, the first valid one to be used: a value of its type that differs,
// and for a name or reference one that keeps the scene's references valid.
template <class M>
std::vector<M> other_values(const M& v, unsigned flags, const Scene& s) {
  std::vector<M> out;
  if constexpr (std::is_same_v<M, float>) {
    out = {v + 0.25f, v - 0.25f};
  } else if constexpr (std::is_enum_v<M>) {
    for (M e : EnumNames<M>::values)
      if (e != v) out.push_back(e);
  } else if constexpr (std::is_integral_v<M>) {
    out = {static_cast<M>(v + 1), static_cast<M>(v - 1)};
  } else if constexpr (std::is_same_v<M, glm::vec3> || std::is_same_v<M, glm::vec2>) {
    for (float d : {0.25f, -0.25f}) {
      M changed = v;
      changed.x += d;
      out.push_back(changed);
    }
  } else if constexpr (std::is_same_v<M, std::string>) {
    if (flags & kTextureRef) {
      for (const Texture& t : s.textures) out.push_back(t.name);
      out.push_back("");
    } else if (flags & kMaterialRef) {
      for (const Material& m : s.materials) out.push_back(m.name);
    } else if (flags & kAssetPath) {
      out = {v.empty() ? "sky.hdr" : "other_" + v};
    } else {
      out = {v + "2"};
    }
  } else if constexpr (std::is_same_v<M, Camera>) {  // a view's camera: moved sideways
    for (float d : {0.25f, -0.25f}) {
      M changed = v;
      changed.position.x += d;
      out.push_back(changed);
    }
  } else {  // arrays of points: the last point moved (the quad keeps its area)
    for (float d : {0.25f, -0.25f}) {
      M changed = v;
      changed.back().x += d;
      out.push_back(changed);
    }
  }
  return out;
}

// Calls fn(key, flags, changed_scene) once for each field of each part of sample_scene(): the
// part itself, or the last element of a list.
template <class Fn>
size_t for_each_field_changed(Fn&& fn) {
  const Scene base = sample_scene();
  size_t fields = 0;
  visit_scene_parts([&](const char* key, auto part_member) {
    auto part_of = [&](Scene& s) -> auto& {
      auto& part = s.*part_member;
      if constexpr (IsVector<std::decay_t<decltype(part)>>::value) return part.back();
      else return part;
    };
    using T = std::decay_t<decltype(part_of(std::declval<Scene&>()))>;
    FieldTable<T>::visit([&](const auto& f) {
      ++fields;
      const std::string what = std::string(key) + "." + f.key;
      Scene copy = base;
      const auto original = part_of(copy).*f.member;
      bool changed = false;
      for (const auto& value : other_values(original, f.flags, base)) {
        if (value == original) continue;
        part_of(copy).*f.member = value;
        if (validate_scene(copy, false).empty()) {
          changed = true;
          break;
        }
        part_of(copy).*f.member = original;
      }
      ASSERT_TRUE(changed) << what << ": no valid other value";
      ASSERT_NE(copy, base) << what;
      fn(what, std::string(key), f.flags, base, copy);
    });
  });
  return fields;
}

constexpr size_t kFields = field_count<Camera>() + field_count<Film>() +
                           field_count<RenderSettings>() + field_count<DisplaySettings>() +
                           field_count<Environment>() + field_count<Texture>() +
                           field_count<Material>() + field_count<Sphere>() + field_count<Quad>() +
                           field_count<CameraView>();

TEST(SceneFields, EveryFieldChangesTheDigestItBelongsTo) {
  const SceneDigests before = digest_scene(sample_scene());
  const size_t fields = for_each_field_changed([&](const std::string& what, const std::string& key,
                                                   unsigned flags, const Scene&, const Scene& changed) {
    const SceneDigests after = digest_scene(changed);
    uint64_t SceneDigests::*expected = (flags & kLabel) ? nullptr : digest_of_part(key);
    for (uint64_t SceneDigests::*d : kAllDigests)
      EXPECT_EQ(after.*d != before.*d, d == expected) << what;
    // Radiance restarts the accumulation; the display only re-runs the tonemap.
    const bool radiance = expected && expected != &SceneDigests::display;
    EXPECT_EQ(after.radiance() != before.radiance(), radiance) << what;
  });
  EXPECT_EQ(fields, kFields);
}

TEST(SceneFields, EveryFieldIsWrittenAndReadBackExactly) {
  const size_t fields = for_each_field_changed([&](const std::string& what, const std::string&,
                                                   unsigned, const Scene& base, const Scene& changed) {
    const std::string text = project_file_text(changed);
    EXPECT_NE(text, project_file_text(base)) << what << " is not written";
    const Scene loaded = load_project_text(text, "changed.glint", changed.base_dir, false);
    EXPECT_EQ(loaded, changed) << what << " does not read back:\n" << text;
    EXPECT_EQ(project_file_text(loaded), text) << what;
  });
  EXPECT_EQ(fields, kFields);
}

// Asset paths: the digest covers the file's size, so that a texture edited on disk is uploaded
// again.
TEST(SceneFields, AnAssetFileChangedOnDiskChangesItsDigest) {
  test::TempDir dir;
  Scene s = sample_scene();
  s.base_dir = dir.path();
  s.environment.texture = "sky.hdr";
  std::ofstream(dir / "wood.png") << "1";
  std::ofstream(dir / "sky.hdr") << "1";
  const SceneDigests before = digest_scene(s);
  std::ofstream(dir / "wood.png") << "12";
  std::ofstream(dir / "sky.hdr") << "12";
  const SceneDigests after = digest_scene(s);
  EXPECT_NE(after.textures, before.textures);
  EXPECT_NE(after.environment, before.environment);
  EXPECT_EQ(after.materials, before.materials);
}

}  // namespace
}  // namespace glint
