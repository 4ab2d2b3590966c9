// The material panel's Preset menu (editor/material_presets.h): one choice sets the type,
// roughness, IOR and, for metals and glass, the colour; like any edit, one undo step.
#include "editor/material_presets.h"
#include "editor/ui.h"
#include "editor/ui_tip.h"

namespace glint {

void draw_material_preset_combo(Material& m) {
  const MaterialPreset* current = matching_preset(m);
  if (ImGui::BeginCombo("Preset", current ? current->name : "(custom)")) {
    for (const MaterialPreset& p : kMaterialPresets) {
      if (ImGui::Selectable(p.name, &p == current)) apply_material_preset(m, p);
      tip(p.summary);
    }
    ImGui::EndCombo();
  }
  tip("Real materials: glass, water and diamond by their IOR; gold, silver, copper and\n"
      "aluminium by their measured reflectance; plastic and rubber keep the colour.");
}

}  // namespace glint
