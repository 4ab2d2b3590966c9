// Region render and the live error map in the viewport. As Blender's render region: Ctrl+B (or
// the toolbar's Region button) arms the region tool, a left drag draws the rectangle, and from
// then on only its pixels take samples (GpuRenderer::set_sample_region); Ctrl+Alt+B or Clear
// region samples everything again. The error map lays each pixel's estimated relMSE over the
// image as a heat colour (renderer/error_map.h). Neither is saved or undone: they are how the
// viewport samples and shows, like the preview resolution.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "editor/ui.h"
#include "editor/ui_context.h"
#include "editor/ui_tip.h"
#include "renderer/error_map.h"

namespace glint {
namespace {

// A drag shorter than this (ImGui units, per side) is a click, not a region.
constexpr float kMinRegionSide = 4;

FractionRect fraction_rect(ImVec2 a, ImVec2 b, ImVec2 origin, ImVec2 size) {
  auto fx = [&](float x) { return std::clamp((x - origin.x) / size.x, 0.0f, 1.0f); };
  auto fy = [&](float y) { return std::clamp((y - origin.y) / size.y, 0.0f, 1.0f); };
  return {std::min(fx(a.x), fx(b.x)), std::min(fy(a.y), fy(b.y)), std::max(fx(a.x), fx(b.x)),
          std::max(fy(a.y), fy(b.y))};
}

void dashed_rect(ImDrawList* dl, ImVec2 a, ImVec2 b, ImU32 colour) {
  dl->AddRect(a, b, IM_COL32(0, 0, 0, 160), 0, 0, 3.0f);
  dl->AddRect(a, b, colour, 0, 0, 1.5f);
}

}  // namespace

void clear_region(EditorState& state) {
  state.viewport.region.reset();
  state.tools.region_tool = false;
  state.tools.region_dragging = false;
}

void handle_region_shortcuts(EditorState& state) {
  const ImGuiIO& io = ImGui::GetIO();
  if (!io.KeyCtrl || io.KeyShift || !ImGui::IsKeyPressed(ImGuiKey_B, false)) return;
  if (io.KeyAlt) {
    clear_region(state);
    show_message(state, "Region cleared: the whole image takes samples");
  } else {
    state.tools.region_tool = !state.tools.region_tool;
    if (state.tools.region_tool) show_message(state, "Drag a rectangle in the viewport to render only there");
  }
}

bool region_drag(EditorState& state, ImVec2 origin, ImVec2 size, bool hovered) {
  ViewportTools& tools = state.tools;
  const ImGuiIO& io = ImGui::GetIO();
  if (!tools.region_tool && !tools.region_dragging) return false;
  if (!tools.region_dragging) {
    if (!(hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left))) return false;
    tools.region_dragging = true;
    tools.region_start = io.MousePos;
    return true;
  }
  const ImVec2 a = tools.region_start, b = io.MousePos;
  if (ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
    dashed_rect(ImGui::GetWindowDrawList(), ImVec2(std::min(a.x, b.x), std::min(a.y, b.y)),
                ImVec2(std::max(a.x, b.x), std::max(a.y, b.y)), IM_COL32(255, 200, 60, 255));
    return true;
  }
  tools.region_dragging = false;
  tools.region_tool = false;
  if (std::abs(b.x - a.x) >= kMinRegionSide && std::abs(b.y - a.y) >= kMinRegionSide)
    state.viewport.region = fraction_rect(a, b, origin, size);
  return true;
}

void draw_region_toolbar(EditorState& state, ImVec2 top_right) {
  ViewportTools& tools = state.tools;
  ViewportView& view = state.viewport;
  const ImGuiStyle& style = ImGui::GetStyle();
  auto width = [&](const char* label) { return ImGui::CalcTextSize(label, nullptr, true).x + 2 * style.FramePadding.x; };
  const bool has_region = view.region.has_value();
  float total = width("Region") + width("Error map") + style.ItemSpacing.x;
  if (has_region) total += width("Clear region") + style.ItemSpacing.x;
  ImGui::SetCursorScreenPos(ImVec2(top_right.x - total, top_right.y));
  auto toggle = [&](const char* label, bool on) {
    if (on) ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_ButtonActive));
    const bool pressed = ImGui::Button(label);
    if (on) ImGui::PopStyleColor();
    return pressed;
  };
  if (toggle("Region", tools.region_tool)) tools.region_tool = !tools.region_tool;
  tip("Render region (Ctrl+B): drag a rectangle in the viewport; only its pixels take samples.");
  if (has_region) {
    ImGui::SameLine();
    if (ImGui::Button("Clear region")) clear_region(state);
    tip("Sample the whole image again (Ctrl+Alt+B).");
  }
  ImGui::SameLine();
  if (toggle("Error map", view.error_map)) view.error_map = !view.error_map;
  tip("Overlay each pixel's estimated error (relMSE, the figure in the status line per pixel):\n"
      "blue 1e-4 and below, red 1 and above; pixels with fewer than 2 samples are clear.");
}

void draw_region_overlays(const ViewportView& view, ImDrawList* dl) {
  const ImVec2 origin = view.pos;
  const ImVec2 end(origin.x + view.size.x, origin.y + view.size.y);
  if (view.error_map && view.frame.error_map_texture) {
    dl->AddImage(static_cast<ImTextureID>(view.frame.error_map_texture), origin, end);
    // The legend: the ramp from kErrorMapLow to kErrorMapHigh, bottom right.
    const float w = ui_units(120), h = ui_units(8);
    const ImVec2 at(end.x - w - ui_units(10), end.y - h - ui_units(24));
    const int steps = 24;
    const float log_low = std::log10(kErrorMapLow), log_high = std::log10(kErrorMapHigh);
    for (int i = 0; i < steps; ++i) {
      const float r = std::pow(10.0f, log_low + (log_high - log_low) * (i + 0.5f) / steps);
      const glm::vec3 c = error_map_colour(r);
      dl->AddRectFilled(ImVec2(at.x + w * i / steps, at.y), ImVec2(at.x + w * (i + 1) / steps, at.y + h),
                        ImGui::GetColorU32(ImVec4(c.r, c.g, c.b, 1)));
    }
    char text[64];
    std::snprintf(text, sizeof text, "relMSE %.0e .. %.0e", kErrorMapLow, kErrorMapHigh);
    dl->AddText(ImVec2(at.x, at.y + h + 2), IM_COL32(255, 255, 255, 220), text);
  }
  if (view.region) {
    const FractionRect& r = *view.region;
    dashed_rect(dl, ImVec2(origin.x + r.x0 * view.size.x, origin.y + r.y0 * view.size.y),
                ImVec2(origin.x + r.x1 * view.size.x, origin.y + r.y1 * view.size.y), IM_COL32(255, 200, 60, 255));
  }
}

}  // namespace glint
