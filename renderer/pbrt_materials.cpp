#include "renderer/pbrt_materials.h"

#include <algorithm>
#include <cmath>

#include "renderer/json_fields.h"

namespace glint::pbrt {

// A Glint texture for a pbrt texture's name ("" when the file declared no image texture of it).
std::string MaterialReader::glint_texture(const std::string& name) {
  const auto found = image_textures.find(name);
  if (found == image_textures.end()) {
    warn("texture \"" + json_fields::clip(name, 40) + "\" is not an image texture read so far: not imported");
    return "";
  }
  if (find_texture(scene, name) < 0) scene.textures.push_back({name, found->second});
  return name;
}

// Glint's roughness r (alpha = r^2) from pbrt's roughness parameters.
float MaterialReader::roughness(const Params& ps) {
  double value = ps.number("roughness", 0);
  if (ps.find("uroughness") || ps.find("vroughness")) {
    value = ps.number("uroughness", 0);
    if (ps.number("vroughness", 0) != value) warn("anisotropic roughness is read as uroughness (Glint's is isotropic)");
  }
  const double alpha = ps.boolean("remaproughness", true) ? std::sqrt(std::max(0.0, value)) : value;
  return float(std::sqrt(std::max(0.0, alpha)));
}

glm::vec3 MaterialReader::colour(const Params& ps, const std::string& name, glm::vec3 fallback, Material& m) {
  if (const std::string tex = ps.texture(name); !tex.empty()) {
    m.color_texture = glint_texture(tex);
    return glm::vec3(1);
  }
  return ps.rgb(name, fallback);
}

std::string MaterialReader::read(const std::string& name, const std::string& type, const Params& ps) {
  Material m;
  if (type == "diffuse") {
    m.color = colour(ps, "reflectance", glm::vec3(0.5f), m);
  } else if (type == "conductor") {
    m.type = MaterialType::reflective;
    if (!ps.find("reflectance")) warn("its metal's complex index of refraction is read as a white mirror");
    ps.find("eta"), ps.find("k");
    m.color = colour(ps, "reflectance", glm::vec3(1), m);
    m.roughness = roughness(ps);
  } else if (type == "coateddiffuse") {
    m.type = MaterialType::glossy;
    m.color = colour(ps, "reflectance", glm::vec3(0.5f), m);
    m.roughness = roughness(ps);
    m.ior = float(ps.number("eta", 1.5));
    ps.find("thickness");
    warn("read as Glint's glossy (a clear coat over a diffuse base, which layers them differently)");
  } else if (type == "dielectric" || type == "thindielectric") {
    m.type = type == "dielectric" ? MaterialType::refractive : MaterialType::transparent;
    m.ior = float(ps.number("eta", 1.5));
    m.color = glm::vec3(1);  // pbrt's glass has no tint
    m.roughness = type == "dielectric" ? roughness(ps) : 0.0f;
    if (type == "thindielectric") warn("read as Glint's transparent (thin glass with Schlick's Fresnel, no inter-reflections)");
  } else {
    warn("material type \"" + json_fields::clip(type, 40) + "\" is read as a grey matte");
    m.color = glm::vec3(0.5f);
    for (const auto& p : ps.list) p.used = true;
  }
  ps.find("type");
  ps.find("displacement") ? warn("its displacement is not imported") : void();
  std::string unique = name;
  for (int n = 2; find_material(scene, unique) >= 0; ++n) unique = name + "-" + std::to_string(n);
  m.name = unique;
  scene.materials.push_back(m);
  return unique;
}

}  // namespace glint::pbrt
