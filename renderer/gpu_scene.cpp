#include "renderer/gpu_scene.h"

#include <algorithm>

namespace glint {
namespace {

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

}  // namespace

PackedScene pack_scene(const Scene& scene) {
  PackedScene packed;
  for (const Material& m : scene.materials) {
    GpuMaterial g{};
    g.color = glm::vec4(m.color, static_cast<float>(static_cast<int>(m.type)));
    g.emission = glm::vec4(m.emission, 0);
    g.params = glm::vec4(m.roughness, m.ior, m.opacity, 0);
    g.layers = glm::ivec4(layer_for(scene, m.color_texture, ColorEncoding::srgb, packed.layers),
                          layer_for(scene, m.emission_texture, ColorEncoding::srgb, packed.layers),
                          layer_for(scene, m.roughness_texture, ColorEncoding::linear, packed.layers),
                          -1);
    packed.materials.push_back(g);
  }
  for (const Sphere& s : scene.spheres)
    packed.spheres.push_back({glm::vec4(s.center, s.radius),
                              glm::ivec4(material_index(scene, s.material), 0, 0, 0)});
  for (const Quad& q : scene.quads) {
    GpuQuad g{};
    g.p0 = glm::vec4(q.corners[0], 0);
    g.p1 = glm::vec4(q.corners[1], 0);
    g.p2 = glm::vec4(q.corners[2], 0);
    g.p3 = glm::vec4(q.corners[3], 0);
    g.uv01 = glm::vec4(q.uvs[0], q.uvs[1]);
    g.uv23 = glm::vec4(q.uvs[2], q.uvs[3]);
    g.normal = glm::vec4(
        glm::normalize(glm::cross(q.corners[1] - q.corners[0], q.corners[2] - q.corners[0])), 0);
    g.material = glm::ivec4(material_index(scene, q.material), 0, 0, 0);
    packed.quads.push_back(g);
  }
  return packed;
}

}  // namespace glint
