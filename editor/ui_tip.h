// The hover help of the item just drawn: every property, button and row of the panels has one.
#pragma once

#include <imgui.h>

namespace glint {

// Shown at once while the item is hovered (a panel's fields, buttons and choices), also
// while it is disabled, where it says what the item would do.
inline void tip(const char* text) {
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("%s", text);
}

// Shown once the mouse rests on the item a moment (ImGui's tooltip delay), for items passed
// over often, such as the outliner's rows.
inline void resting_tip(const char* text) {
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_ForTooltip)) ImGui::SetTooltip("%s", text);
}

}  // namespace glint
