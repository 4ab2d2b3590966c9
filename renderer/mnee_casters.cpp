#include "renderer/mnee_casters.h"

#include <algorithm>

#include "renderer/quad_shape.h"

namespace glint {
namespace {

// shaders/lib/bsdf.glsl's DELTA_ROUGHNESS: below it a mirror or refractive surface is smooth.
constexpr float kDeltaRoughness = 0.03f;

// A validated scene's material of a shape (an unresolved name falls back to material 0 as in
// pack_scene).
const Material* material_of(const Scene& scene, const std::string& name) {
  if (scene.materials.empty()) return nullptr;
  return &scene.materials[static_cast<size_t>(std::max(find_material(scene, name), 0))];
}

bool emits(const Material& m) { return m.emission != glm::vec3(0); }

bool is_delta(const Material& m) {
  const bool smooth = m.roughness < kDeltaRoughness && m.roughness_texture.empty();
  if (m.type == MaterialType::refractive) return smooth || m.ior == 1.0f;
  return (m.type == MaterialType::reflective || m.type == MaterialType::transparent) && smooth;
}

// An emitting sphere or parallelogram quad: a lamp MNEE samples.
bool has_sampled_lamp(const Scene& scene) {
  bool lamp = false;
  for (const Sphere& s : scene.spheres) {
    const Material* m = material_of(scene, s.material);
    lamp = lamp || (m && emits(*m));
  }
  for (const Quad& q : scene.quads) {
    const Material* m = material_of(scene, q.material);
    lamp = lamp || (m && emits(*m) && quad_is_parallelogram(q.corners));
  }
  return lamp;
}

// An environment map that MNEE (and next-event estimation) sample.
bool has_environment_map(const Scene& scene) {
  return !scene.environment.texture.empty() && scene.environment.intensity > 0;
}

// Whether every surface that is neither a lamp nor smooth (delta) is matte.
bool only_matte_receivers(const Scene& scene) {
  auto matte = [&](const std::string& name) {
    const Material* m = material_of(scene, name);
    return !m || emits(*m) || is_delta(*m) || m->type == MaterialType::matte;
  };
  for (const Sphere& s : scene.spheres)
    if (!matte(s.material)) return false;
  for (const Quad& q : scene.quads)
    if (!matte(q.material)) return false;
  return true;
}

}  // namespace

bool is_mnee_caster_material(const Material& m) {
  return (m.type == MaterialType::reflective || m.type == MaterialType::refractive ||
          m.type == MaterialType::transparent) &&
         m.roughness < kDeltaRoughness && m.roughness_texture.empty() && m.color_texture.empty() &&
         m.opacity >= 1.0f && !emits(m) && (m.type != MaterialType::refractive || m.ior > 0.0f);
}

std::vector<int> mnee_casters(const Scene& scene) {
  std::vector<int> out;
  for (size_t i = 0; i < scene.spheres.size() && out.size() < size_t(kMaxMneeCasters); ++i) {
    const Material* m = material_of(scene, scene.spheres[i].material);
    if (m && is_mnee_caster_material(*m) && scene.spheres[i].radius > 0) out.push_back(static_cast<int>(i));
  }
  return out;
}

int mnee_lights(const Scene& scene, double environment_peak_share, bool always) {
  if (!scene_needs_mnee(scene)) return 0;
  int lights = 0;
  if (has_sampled_lamp(scene) && (always || mnee_pays_off(scene))) lights |= kMneeLamps;
  if (has_environment_map(scene) &&
      (always || (environment_peak_share >= kMneePeakedEnvironmentShare && only_matte_receivers(scene))))
    lights |= kMneeEnvironment;
  return lights;
}

bool mnee_pays_off(const Scene& scene) {
  if (!scene_needs_mnee(scene)) return false;
  double largest_cross_section = 0;
  for (int i : mnee_casters(scene)) {
    const double r = scene.spheres[static_cast<size_t>(i)].radius;
    largest_cross_section = std::max(largest_cross_section, 3.14159265358979 * r * r);
  }
  double smallest_lamp = -1;
  auto lamp = [&](const Material* m, double area) {
    if (m && emits(*m) && area > 0 && (smallest_lamp < 0 || area < smallest_lamp)) smallest_lamp = area;
  };
  for (const Sphere& s : scene.spheres)
    lamp(material_of(scene, s.material), 4.0 * 3.14159265358979 * double(s.radius) * s.radius);
  for (const Quad& q : scene.quads) {
    if (!quad_is_parallelogram(q.corners)) continue;
    const glm::dvec3 p0(q.corners[0]), p1(q.corners[1]), p2(q.corners[2]);
    lamp(material_of(scene, q.material), glm::length(glm::cross(p1 - p0, p2 - p0)));
  }
  return smallest_lamp >= 0 && smallest_lamp <= kMneeSmallLampShare * largest_cross_section;
}

bool scene_needs_mnee(const Scene& scene) {
  if (mnee_casters(scene).empty()) return false;
  if (!has_environment_map(scene) && !has_sampled_lamp(scene)) return false;
  auto receives = [&](const std::string& name) {
    const Material* m = material_of(scene, name);
    return m && !is_delta(*m);
  };
  for (const Sphere& s : scene.spheres)
    if (receives(s.material)) return true;
  for (const Quad& q : scene.quads)
    if (receives(q.material)) return true;
  return false;
}

}  // namespace glint
