#include "renderer/scene_digest.h"

#include <system_error>
#include <type_traits>

#include "renderer/scene_fields.h"

namespace glint {

void Hasher::bytes(const void* data, size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) {
    state_ ^= p[i];
    state_ *= 1099511628211ull;
  }
}
void Hasher::value(float v) {
  if (v == 0.0f) v = 0.0f;  // -0 and +0 render the same
  bytes(&v, sizeof v);
}
void Hasher::value(int v) { bytes(&v, sizeof v); }
void Hasher::value(uint32_t v) { bytes(&v, sizeof v); }
void Hasher::value(uint64_t v) { bytes(&v, sizeof v); }
void Hasher::value(const glm::vec2& v) {
  value(v.x);
  value(v.y);
}
void Hasher::value(const glm::vec3& v) {
  value(v.x);
  value(v.y);
  value(v.z);
}
void Hasher::value(const std::string& s) {
  value(static_cast<uint64_t>(s.size()));
  bytes(s.data(), s.size());
}

namespace {

// A file's identity for change detection: size and modification time (0 when unreadable).
void file_stamp(Hasher& h, const std::filesystem::path& path) {
  std::error_code ec;
  auto size = std::filesystem::file_size(path, ec);
  h.value(static_cast<uint64_t>(ec ? 0 : size));
  auto time = std::filesystem::last_write_time(path, ec);
  h.value(static_cast<uint64_t>(ec ? 0 : time.time_since_epoch().count()));
}

// The values of an object's fields (scene_fields.h) but labels, and the files of asset paths.
template <class T>
void hash_object(Hasher& h, const Scene& scene, const T& object) {
  FieldTable<T>::visit([&](const auto& f) {
    if (f.has(kLabel)) return;
    const auto& value = object.*f.member;
    using M = typename std::decay_t<decltype(f)>::Type;
    if constexpr (std::is_enum_v<M>) {
      h.value(static_cast<int>(value));
    } else if constexpr (std::is_same_v<M, std::array<glm::vec3, 4>> ||
                         std::is_same_v<M, std::array<glm::vec2, 4>>) {
      for (const auto& row : value) h.value(row);
    } else {
      h.value(value);
    }
    if constexpr (std::is_same_v<M, std::string>)
      if (f.has(kAssetPath) && !value.empty()) file_stamp(h, resolve_asset_path(scene, value));
  });
}

template <class T>
void hash_list(Hasher& h, const Scene& scene, const std::vector<T>& list) {
  h.value(static_cast<uint64_t>(list.size()));
  for (const T& object : list) hash_object(h, scene, object);
}

template <class... Parts>
uint64_t digest_of(const Scene& scene, const Parts&... parts) {
  Hasher h;
  auto one = [&](const auto& part) {
    if constexpr (IsVector<std::decay_t<decltype(part)>>::value) hash_list(h, scene, part);
    else hash_object(h, scene, part);
  };
  (one(parts), ...);
  return h.result();
}

}  // namespace

uint64_t SceneDigests::radiance() const {
  Hasher h;
  for (uint64_t d : {geometry, materials, textures, environment, camera, settings}) h.value(d);
  return h.result();
}

SceneDigests digest_scene(const Scene& scene) {
  // Each part of the scene in one digest; the film is in none: GpuRenderer::sync is given the
  // size to render at (the film's or another) and restarts the accumulation on a new size.
  // The camera views are in none: saving, renaming or deleting a bookmark never resets the
  // render (recalling one changes scene.camera, which is).
  static_assert(scene_part_count() == 10, "a new part of Scene needs its digest here");
  SceneDigests d;
  d.geometry = digest_of(scene, scene.spheres, scene.quads);
  d.materials = digest_of(scene, scene.materials);
  d.textures = digest_of(scene, scene.textures);
  d.environment = digest_of(scene, scene.environment);
  d.camera = digest_of(scene, scene.camera);
  d.settings = digest_of(scene, scene.render);
  d.display = digest_of(scene, scene.display);
  return d;
}

}  // namespace glint
