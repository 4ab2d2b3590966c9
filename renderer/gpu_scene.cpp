#include "renderer/gpu_scene.h"

#include <algorithm>
#include <cmath>

#include "renderer/mnee_casters.h"
#include "renderer/quad_shape.h"
#include "renderer/texture_slots.h"

namespace glint {
namespace {

static_assert(kTextureSlots.size() <= 4, "GpuMaterial::layers holds four texture layers");

int layer_for(const Scene& scene, const std::string& texture_name, ColorEncoding encoding,
              std::vector<TextureLayer>& layers) {
  if (texture_name.empty()) return -1;
  TextureLayer layer{find_texture(scene, texture_name), encoding};
  if (layer.texture < 0) return -1;
  auto it = std::find(layers.begin(), layers.end(), layer);
  if (it != layers.end()) return static_cast<int>(it - layers.begin());
  layers.push_back(layer);
  return static_cast<int>(layers.size()) - 1;
}

int material_index(const Scene& scene, const std::string& name) {
  return std::max(find_material(scene, name), 0);
}

double quad_area(const Quad& q) {
  glm::dvec3 p0(q.corners[0]), p1(q.corners[1]), p2(q.corners[2]), p3(q.corners[3]);
  return 0.5 * (glm::length(glm::cross(p1 - p0, p2 - p0)) + glm::length(glm::cross(p3 - p1, p2 - p1)));
}

// Selection pdfs in proportion to power, accumulated in double so the cdf is monotone and its
// last entry exactly 1 whatever the number of lights.
void add_lights(const Scene& scene, PackedScene& packed) {
  std::vector<double> power;
  auto consider = [&](int kind, int index, const std::string& material, double area, bool parallelogram,
                      glm::ivec4& slot) {
    const Material& m = scene.materials[static_cast<size_t>(material_index(scene, material))];
    double p = emitter_power(m.emission, area);
    if (!(p > 0)) return;
    slot.y = static_cast<int>(packed.lights.size());
    packed.lights.push_back({glm::ivec4(kind, index, parallelogram ? 1 : 0, 0),
                             glm::vec4(0, 0, kind == 1 ? static_cast<float>(area) : 0.0f, 0)});
    power.push_back(p);
  };
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& s = scene.spheres[i];
    consider(0, static_cast<int>(i), s.material, 4.0 * 3.14159265358979 * double(s.radius) * s.radius,
             false, packed.spheres[i].material);
  }
  for (size_t i = 0; i < scene.quads.size(); ++i)
    consider(1, static_cast<int>(i), scene.quads[i].material, quad_area(scene.quads[i]),
             quad_is_parallelogram(scene.quads[i].corners), packed.quads[i].material);
  double total = 0;
  for (double p : power) total += p;
  double running = 0;
  for (size_t i = 0; i < power.size(); ++i) {
    running += power[i];
    packed.lights[i].select = glm::vec4(static_cast<float>(power[i] / total),
                                        i + 1 == power.size() ? 1.0f : static_cast<float>(running / total),
                                        packed.lights[i].select.z, 0);
  }
}

}  // namespace

double emitter_power(const glm::vec3& emission, double area) {
  double lum = 0.2126 * emission.x + 0.7152 * emission.y + 0.0722 * emission.z;
  return std::isfinite(lum * area) ? std::max(lum, 0.0) * area : 0.0;
}

glm::dvec3 render_origin(const glm::vec3& camera_position) {
  glm::dvec3 c(camera_position);
  double m = std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)});
  if (!(m >= 1024.0) || !std::isfinite(m)) return glm::dvec3(0);
  double cell = std::exp2(std::floor(std::log2(m)) - 6.0);
  return glm::round(c / cell) * cell;
}

PackedScene pack_scene(const Scene& scene, const glm::dvec3& origin) {
  auto local = [&](const glm::vec3& p) { return glm::vec3(glm::dvec3(p) - origin); };
  PackedScene packed;
  for (const Material& m : scene.materials) {
    GpuMaterial g{};
    g.color = glm::vec4(m.color, static_cast<float>(static_cast<int>(m.type)));
    g.emission = glm::vec4(m.emission, 0);
    g.params = glm::vec4(m.roughness, m.ior, m.opacity, 0);
    g.layers = glm::ivec4(-1);
    for (size_t slot = 0; slot < kTextureSlots.size(); ++slot)
      g.layers[static_cast<int>(slot)] =
          layer_for(scene, m.*kTextureSlots[slot].member, kTextureSlots[slot].encoding, packed.layers);
    packed.materials.push_back(g);
  }
  for (const Sphere& s : scene.spheres)
    packed.spheres.push_back({glm::vec4(local(s.center), s.radius),
                              glm::ivec4(material_index(scene, s.material), -1, 0, 0)});
  for (const Quad& q : scene.quads) {
    GpuQuad g{};
    g.p0 = glm::vec4(local(q.corners[0]), 0);
    g.p1 = glm::vec4(local(q.corners[1]), 0);
    g.p2 = glm::vec4(local(q.corners[2]), 0);
    g.p3 = glm::vec4(local(q.corners[3]), 0);
    g.uv01 = glm::vec4(q.uvs[0], q.uvs[1]);
    g.uv23 = glm::vec4(q.uvs[2], q.uvs[3]);
    // In double: in float the cross product's squared length overflows from edges of about
    // 1e10 (normalize then gave a zero normal and a black quad), the cross product itself
    // from about 1e19.
    const glm::dvec3 c0(q.corners[0]), c1(q.corners[1]), c2(q.corners[2]);
    g.normal = glm::vec4(glm::vec3(glm::normalize(glm::cross(c1 - c0, c2 - c0))), 0);
    g.material = glm::ivec4(material_index(scene, q.material), -1, 0, 0);
    packed.quads.push_back(g);
  }
  add_lights(scene, packed);
  packed.casters = mnee_casters(scene);
  for (int i : packed.casters) packed.spheres[static_cast<size_t>(i)].material.z = 1;
  return packed;
}

}  // namespace glint
