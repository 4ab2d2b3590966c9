// The editor's Dear ImGui context: docking on, ImPlot's context beside it, a scalable font, the
// dark style, and everything sized by the monitor's content scale (docs/DESIGN.md §2.3). The app
// and the headless UI tests make the context the same way.
#pragma once

namespace glint {

// Creates the ImGui and ImPlot contexts (current from then on) at `content_scale`. Layout
// persistence is the caller's (editor/ui_layout.h): ImGui itself writes no .ini file.
void create_ui_context(float content_scale);
void destroy_ui_context();

// Text and style sizes at `scale` (1 = 96 dpi): the font is rasterised at the scaled size (sharp,
// not stretched) and every padding, spacing and rounding of the dark style is multiplied, as
// are ImPlot's paddings, tick lengths and line sizes.
// Cheap when the scale is unchanged; call it whenever the content scale may have changed.
void set_content_scale(float scale);
float content_scale();
// A size in ImGui units (the sizes at scale 1) in pixels at the current scale, for the fixed
// widths of buttons, labels and thumbnails.
float ui_units(float units);

// GLINT_CONTENT_SCALE (a number from 0.5 to 4), which overrides the monitor's content scale
// (for screenshots under Xvfb, which reports 1); 0 when unset or invalid (a warning
// is printed once for an invalid value).
float content_scale_override();

}  // namespace glint
