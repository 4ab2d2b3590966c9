// The material types in one table (docs/DESIGN.md §7): for each, its name in the project file,
// the shader's integer code, the define that compiles it out of a specialised trace program,
// which of a material's fields it reads, and the editor's one-line summary. A new type is one
// row here (in the enum's order), its lobe in shaders/lib/bsdf.glsl and its chi-square test.
//
// The row's index is the enum's value and the shader's code: gpu_scene.cpp packs
// static_cast<int>(type), and bsdf.glsl compares it with `const int MATERIAL_<NAME> = <index>`
// (unit.MaterialTypes.ShaderCodesMatchTheTable reads the shader's source to check it).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>

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
  const char* name;            // as in the project file
  const char* shader_code;     // the GLSL constant that names the type's code
  const char* omit_define;     // defined in a program for scenes without the type
  unsigned fields;             // MaterialField bits
  const char* summary;         // the Type tooltip
};

inline constexpr MaterialTypeInfo kMaterialTypes[] = {
    {MaterialType::matte, "matte", "MATERIAL_MATTE", "GLINT_NO_MATTE", kFieldColour | kFieldEmission | kFieldOpacity,
     "Diffuse (Lambert): colour is the albedo."},
    {MaterialType::reflective, "reflective", "MATERIAL_REFLECTIVE", "GLINT_NO_REFLECTIVE",
     kFieldColour | kFieldEmission | kFieldRoughness | kFieldOpacity,
     "Metal: colour is the reflectance at normal incidence (Schlick); roughness 0 is a mirror."},
    {MaterialType::glossy, "glossy", "MATERIAL_GLOSSY", "GLINT_NO_GLOSSY",
     kFieldColour | kFieldEmission | kFieldRoughness | kFieldIor | kFieldOpacity,
     "Diffuse base under a clear coat: the coat's Fresnel follows the IOR, its blur the roughness."},
    {MaterialType::transparent, "transparent", "MATERIAL_TRANSPARENT", "GLINT_NO_TRANSPARENT",
     kFieldColour | kFieldEmission | kFieldRoughness | kFieldIor | kFieldOpacity,
     "Thin glass: reflects by Fresnel (IOR) and transmits tinted by colour; roughness frosts it."},
    {MaterialType::refractive, "refractive", "MATERIAL_REFRACTIVE", "GLINT_NO_REFRACTIVE",
     kFieldColour | kFieldEmission | kFieldRoughness | kFieldIor | kFieldOpacity,
     "Solid glass: bends light by Snell's law (IOR inside, 1 outside), exact Fresnel; colour tints\n"
     "each transmission; roughness below 0.03 is smooth, above it GGX frosted glass."},
};
inline constexpr size_t kMaterialTypeCount = std::size(kMaterialTypes);

// The guard: one row per enum value, in the enum's order.
constexpr bool material_table_in_enum_order() {
  for (size_t i = 0; i < kMaterialTypeCount; ++i)
    if (static_cast<size_t>(kMaterialTypes[i].type) != i) return false;
  return true;
}
static_assert(kMaterialTypeCount == static_cast<size_t>(kLastMaterialType) + 1,
              "kMaterialTypes needs one row per MaterialType");
static_assert(material_table_in_enum_order(), "kMaterialTypes must list the types in the enum's order");

// Every type, in the table's order (the project file's list of valid names).
constexpr std::array<MaterialType, kMaterialTypeCount> all_material_types() {
  std::array<MaterialType, kMaterialTypeCount> types{};
  for (size_t i = 0; i < kMaterialTypeCount; ++i) types[i] = kMaterialTypes[i].type;
  return types;
}

constexpr const MaterialTypeInfo& material_type_info(MaterialType type) {
  return kMaterialTypes[static_cast<size_t>(type)];
}

inline bool uses_field(MaterialType type, MaterialField field) {
  return (material_type_info(type).fields & field) != 0;
}

}  // namespace glint
