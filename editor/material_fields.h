// Which of a material's fields each material type uses, in one table: the properties panel
// shows only those, and the Add menu lists the types from it, so a new type is one entry here.
// What each type reads is in shaders/lib/bsdf.glsl (colour, roughness and ior per lobe) and
// renderer/gpu_scene.cpp (emission and opacity are read for every type).
#pragma once

#include "renderer/scene.h"

namespace glint {

enum MaterialField : unsigned {
  kFieldColour = 1u << 0,     // with its texture
  kFieldEmission = 1u << 1,   // with its texture and strength
  kFieldRoughness = 1u << 2,  // with its texture
  kFieldIor = 1u << 3,
  kFieldOpacity = 1u << 4,
};

struct MaterialTypeInfo {
  MaterialType type;
  const char* name;     // as in the project file
  unsigned fields;      // MaterialField bits
  const char* summary;  // the Type tooltip
};

inline constexpr MaterialTypeInfo kMaterialTypes[] = {
    {MaterialType::matte, "matte", kFieldColour | kFieldEmission | kFieldOpacity,
     "Diffuse (Lambert): colour is the albedo."},
    {MaterialType::reflective, "reflective", kFieldColour | kFieldEmission | kFieldRoughness | kFieldOpacity,
     "Metal: colour is the reflectance at normal incidence (Schlick); roughness 0 is a mirror."},
    {MaterialType::glossy, "glossy", kFieldColour | kFieldEmission | kFieldRoughness | kFieldIor | kFieldOpacity,
     "Diffuse base under a clear coat: the coat's Fresnel follows the IOR, its blur the roughness."},
    {MaterialType::transparent, "transparent",
     kFieldColour | kFieldEmission | kFieldRoughness | kFieldIor | kFieldOpacity,
     "Thin glass: reflects by Fresnel (IOR) and transmits tinted by colour; roughness frosts it."},
    {MaterialType::refractive, "refractive",
     kFieldColour | kFieldEmission | kFieldRoughness | kFieldIor | kFieldOpacity,
     "Solid glass: bends light by Snell's law (IOR inside, 1 outside), exact Fresnel; colour tints\n"
     "each transmission; roughness below 0.03 is smooth, above it GGX frosted glass."},
};

inline const MaterialTypeInfo* material_type_info(MaterialType type) {
  for (const MaterialTypeInfo& t : kMaterialTypes)
    if (t.type == type) return &t;
  return nullptr;
}

inline bool uses_field(MaterialType type, MaterialField field) {
  const MaterialTypeInfo* t = material_type_info(type);
  return t == nullptr || (t->fields & field) != 0;  // unknown types show everything
}

}  // namespace glint
