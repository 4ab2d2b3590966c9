#include "renderer/scene_digest.h"

#include <system_error>

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

}  // namespace

uint64_t SceneDigests::radiance() const {
  Hasher h;
  for (uint64_t d : {geometry, materials, textures, environment, camera, settings}) h.value(d);
  return h.result();
}

SceneDigests digest_scene(const Scene& scene) {
  SceneDigests d;
  {
    Hasher h;
    h.value(static_cast<uint64_t>(scene.spheres.size()));
    for (const auto& s : scene.spheres) {
      h.value(s.center);
      h.value(s.radius);
      h.value(s.material);
    }
    h.value(static_cast<uint64_t>(scene.quads.size()));
    for (const auto& q : scene.quads) {
      for (const auto& c : q.corners) h.value(c);
      for (const auto& uv : q.uvs) h.value(uv);
      h.value(q.material);
    }
    d.geometry = h.result();
  }
  {
    Hasher h;
    h.value(static_cast<uint64_t>(scene.materials.size()));
    for (const auto& m : scene.materials) {
      h.value(m.name);
      h.value(static_cast<int>(m.type));
      h.value(m.color);
      h.value(m.color_texture);
      h.value(m.emission);
      h.value(m.emission_texture);
      h.value(m.roughness);
      h.value(m.roughness_texture);
      h.value(m.ior);
      h.value(m.opacity);
    }
    d.materials = h.result();
  }
  {
    Hasher h;
    h.value(static_cast<uint64_t>(scene.textures.size()));
    for (const auto& t : scene.textures) {
      h.value(t.name);
      h.value(t.path);
      file_stamp(h, resolve_asset_path(scene, t.path));
    }
    d.textures = h.result();
  }
  {
    Hasher h;
    const auto& e = scene.environment;
    h.value(e.color);
    h.value(e.texture);
    if (!e.texture.empty()) file_stamp(h, resolve_asset_path(scene, e.texture));
    h.value(e.intensity);
    h.value(e.rotation_deg);
    d.environment = h.result();
  }
  {
    Hasher h;
    const auto& c = scene.camera;
    h.value(c.position);
    h.value(c.target);
    h.value(c.up);
    h.value(c.vfov_deg);
    h.value(c.aperture_radius);
    h.value(c.focus_distance);
    d.camera = h.result();
  }
  {
    Hasher h;
    h.value(scene.render.max_bounces);
    h.value(scene.render.seed);
    d.settings = h.result();
  }
  {
    Hasher h;
    h.value(scene.display.exposure);
    h.value(static_cast<int>(scene.display.tonemap));
    d.display = h.result();
  }
  return d;
}

}  // namespace glint
