// A material's texture slots, listed once: each names its member of Material (scene.h), the
// project file's key, how its 8-bit texels are decoded, and what the editor calls it. The GPU
// scene (gpu_scene.cpp), the editor's properties panel and its texture edits (deleting or
// renaming a texture clears or renames every slot that names it) walk this table.
//
// Table order is the order of GpuMaterial::layers (shaders/lib/trace_scene_tables.glsl: x colour,
// y emission, z roughness). A texture slot added to Material and to its field table
// (scene_fields.h, flagged kTextureRef) fails to compile there until it is listed here.
#pragma once

#include <array>
#include <cstddef>
#include <string>

#include "renderer/image.h"
#include "renderer/scene.h"

namespace glint {

struct TextureSlot {
  const char* key;  // the project file's key
  std::string Material::*member;
  ColorEncoding encoding;
  const char* label;  // the properties panel's
  const char* what;   // what the slot's image does (the panel's tip)
};

inline constexpr std::array<TextureSlot, 3> kTextureSlots = {{
    {"color_texture", &Material::color_texture, ColorEncoding::srgb, "Colour tex",
     "An image that replaces the colour (its alpha is coverage)."},
    {"emission_texture", &Material::emission_texture, ColorEncoding::srgb, "Emission tex",
     "An image that multiplies the emission."},
    {"roughness_texture", &Material::roughness_texture, ColorEncoding::linear, "Rough. tex",
     "An image whose first channel replaces the roughness."},
}};

// The index of the slot of a member of Material (kTextureSlots.size() where it is none).
constexpr size_t texture_slot_index(std::string Material::*member) {
  for (size_t i = 0; i < kTextureSlots.size(); ++i)
    if (kTextureSlots[i].member == member) return i;
  return kTextureSlots.size();
}

}  // namespace glint
