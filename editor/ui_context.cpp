#include "editor/ui_context.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>

#include <imgui.h>
#include <implot.h>

namespace glint {
namespace {

float g_scale = 0;  // the scale the style was built for; 0: none yet

// Keeps the scale sensible whatever a driver or the environment reports.
float clamp_scale(float s) { return std::isfinite(s) ? std::fmin(std::fmax(s, 0.5f), 4.0f) : 1.0f; }

// ImPlot's sizes (pixels at scale 1) times the scale, from its default style as ImGui's are:
// paddings, tick lengths, line thicknesses, the default and minimum plot sizes. Alphas and the
// fit padding (a fraction) stay. (The curves' line weight is set per plot: plot_time_series.)
ImPlotStyle scaled_plot_style(float scale) {
  ImPlotStyle s;
  for (ImVec2* v : {&s.PlotDefaultSize, &s.PlotMinSize, &s.MajorTickLen, &s.MinorTickLen, &s.MajorTickSize,
                    &s.MinorTickSize, &s.MajorGridSize, &s.MinorGridSize, &s.PlotPadding, &s.LabelPadding,
                    &s.LegendPadding, &s.LegendInnerPadding, &s.LegendSpacing, &s.MousePosPadding,
                    &s.AnnotationPadding})
    *v = ImVec2(v->x * scale, v->y * scale);
  for (float* f : {&s.PlotBorderSize, &s.DigitalPadding, &s.DigitalSpacing}) *f *= scale;
  return s;
}

}  // namespace

void create_ui_context(float scale) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImPlot::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // the layout is loaded and saved atomically by ui_layout
  io.ConfigFlags |= ImGuiConfigFlags_DockingEnable;
  io.ConfigWindowsMoveFromTitleBarOnly = true;  // a drag in the viewport never moves its window
  // A number field clicked without a drag starts typing, as in Blender (a double click needs two
  // clicks within 0.3 s of frame time, which a slow frame misses; Ctrl+click still works).
  io.ConfigDragClickToInputText = true;
  // Dear ImGui's embedded scalable font: rasterised at whatever size the scale asks for.
  io.Fonts->AddFontDefaultVector();
  g_scale = 0;
  set_content_scale(scale);
}

void destroy_ui_context() {
  ImPlot::DestroyContext();
  ImGui::DestroyContext();
  g_scale = 0;
}

void set_content_scale(float scale) {
  scale = clamp_scale(scale);
  if (scale == g_scale) return;
  g_scale = scale;
  // Scaling an already scaled style would compound the rounding: start from the base style.
  ImGuiStyle style;
  ImGui::StyleColorsDark(&style);
  style.ScaleAllSizes(scale);
  style.FontScaleDpi = scale;
  ImGui::GetStyle() = style;
  if (ImPlot::GetCurrentContext()) ImPlot::GetStyle() = scaled_plot_style(scale);
}

float content_scale() { return g_scale; }

float ui_units(float units) { return units * ImGui::GetStyle().FontScaleDpi; }

float content_scale_override() {
  static bool warned = false;
  const char* text = std::getenv("GLINT_CONTENT_SCALE");
  if (!text || !*text) return 0;
  char* end = nullptr;
  const float s = std::strtof(text, &end);
  if (*end || !(s >= 0.5f && s <= 4.0f)) {
    if (!warned) std::fprintf(stderr, "glint: GLINT_CONTENT_SCALE expects a number from 0.5 to 4, got '%s'; ignored\n", text);
    warned = true;
    return 0;
  }
  return s;
}

}  // namespace glint
