#include "editor/material_presets.h"

namespace glint {

void apply_material_preset(Material& m, const MaterialPreset& p) {
  m.type = p.type;
  m.roughness = p.roughness;
  m.ior = p.ior;
  m.roughness_texture.clear();
  if (p.sets_colour) {
    m.color = p.colour;
    m.color_texture.clear();
  }
}

const MaterialPreset* matching_preset(const Material& m) {
  for (const MaterialPreset& p : kMaterialPresets) {
    const bool colour = !p.sets_colour || (m.color == p.colour && m.color_texture.empty());
    if (m.type == p.type && m.roughness == p.roughness && m.ior == p.ior && colour &&
        m.roughness_texture.empty())
      return &p;
  }
  return nullptr;
}

}  // namespace glint
