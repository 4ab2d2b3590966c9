// Material presets: a small library of real materials applied to the selected material (the
// properties panel's Preset menu). One table, checked at compile time.
//
// Metals are the reflective type, whose colour is the reflectance at normal incidence (F0,
// Schlick). Their linear-sRGB F0 values are computed from measured spectral data (the complex
// index of refraction n + ik, integrated against the CIE observer) in N. Hoffman, "Physics and
// Math of Shading", SIGGRAPH 2015 Physically Based Shading course, the table reproduced in
// Real-Time Rendering 4th ed. (Table 9.2) and in Unity Shader Graph's Metal Reflectance node.
// Indices of refraction at visible wavelengths (about 589 nm): window glass 1.5, water 1.33,
// diamond 2.42, acrylic (PMMA) plastic 1.49, natural rubber 1.52.
#pragma once

#include <initializer_list>
#include <iterator>
#include <string_view>

#include <glm/glm.hpp>

#include "renderer/material_types.h"
#include "renderer/scene.h"

namespace glint {

struct MaterialPreset {
  const char* name;
  MaterialType type;
  bool sets_colour;  // false: the material keeps its colour (plastics and rubbers come in any)
  glm::vec3 colour;  // linear RGB (F0 for metals, the tint of glass)
  float roughness;
  float ior;         // for the types that read it (material_types.h); 1.5 otherwise
  const char* summary;
};

inline constexpr MaterialPreset kMaterialPresets[] = {
    {"Glass", MaterialType::refractive, true, {1, 1, 1}, 0, 1.5f, "Clear solid glass, IOR 1.5."},
    {"Water", MaterialType::refractive, true, {1, 1, 1}, 0, 1.33f, "Clear water, IOR 1.33."},
    {"Diamond", MaterialType::refractive, true, {1, 1, 1}, 0, 2.42f, "Diamond, IOR 2.42."},
    {"Gold", MaterialType::reflective, true, {1.000f, 0.766f, 0.336f}, 0, 1.5f,
     "Polished gold: a mirror with gold's measured F0."},
    {"Silver", MaterialType::reflective, true, {0.972f, 0.960f, 0.915f}, 0, 1.5f,
     "Polished silver: a mirror with silver's measured F0."},
    {"Copper", MaterialType::reflective, true, {0.955f, 0.637f, 0.538f}, 0.2f, 1.5f,
     "Copper with a soft sheen (roughness 0.2), measured F0."},
    {"Aluminium", MaterialType::reflective, true, {0.913f, 0.921f, 0.925f}, 0.35f, 1.5f,
     "Brushed aluminium (roughness 0.35), measured F0."},
    {"Plastic", MaterialType::glossy, false, {0, 0, 0}, 0.08f, 1.49f,
     "Shiny plastic: the colour under a clear acrylic coat (IOR 1.49)."},
    {"Rubber", MaterialType::glossy, false, {0, 0, 0}, 0.6f, 1.52f,
     "Rubber: the colour under a rough coat (IOR 1.52)."},
};

// The guard: names unique and non-empty, values within the project file's checks and
// physically plausible (F0 and tints in [0, 1], roughness in [0, 1], IOR from 1 to 3).
constexpr bool material_presets_are_valid() {
  for (size_t i = 0; i < std::size(kMaterialPresets); ++i) {
    const MaterialPreset& p = kMaterialPresets[i];
    if (std::string_view(p.name).empty() || !(p.roughness >= 0 && p.roughness <= 1)) return false;
    if (!(p.ior >= 1 && p.ior <= 3)) return false;
    for (float c : {p.colour.x, p.colour.y, p.colour.z})
      if (!(c >= 0 && c <= 1)) return false;
    for (size_t j = 0; j < i; ++j)
      if (std::string_view(p.name) == kMaterialPresets[j].name) return false;
  }
  return true;
}
static_assert(material_presets_are_valid(), "a material preset has an invalid value or a duplicate name");

// Applies preset `p` to `m`: its type, roughness and IOR, and (sets_colour) its colour, which
// then replaces a colour texture. The name, emission, opacity and the other textures stay.
void apply_material_preset(Material& m, const MaterialPreset& p);
// The preset `m` matches (type, roughness, IOR and, where the preset sets it, colour), or null.
const MaterialPreset* matching_preset(const Material& m);

}  // namespace glint
