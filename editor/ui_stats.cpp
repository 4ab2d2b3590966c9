// The Render statistics panel: the viewport's samples per pixel per second against the time
// since its accumulation started and, once an estimator feeds it, the estimated error; drawn
// with ImPlot.
#include <algorithm>

#include <implot.h>

#include "editor/ui.h"
#include "editor/ui_context.h"

namespace glint {

void plot_time_series(const char* plot_id, const TimeSeries& series, bool log_y, float height) {
  if (!ImPlot::BeginPlot(plot_id, ImVec2(-1, height), ImPlotFlags_NoMenus | ImPlotFlags_NoBoxSelect)) return;
  // The legend names the curve; the y axis stays unlabelled (a long name would be cut).
  // A log axis gets its range from the positive values (log_axis_range), else a fixed decade:
  // ImPlot's fit of an empty or one-point series is degenerate there.
  ImPlot::SetupAxes("seconds", nullptr, ImPlotAxisFlags_AutoFit, log_y ? ImPlotAxisFlags_None : ImPlotAxisFlags_AutoFit);
  if (log_y) {
    ImPlot::SetupAxisScale(ImAxis_Y1, ImPlotScale_Log10);
    const std::optional<LogRange> range = log_axis_range(series);
    ImPlot::SetupAxisLimits(ImAxis_Y1, range ? range->lo : 1e-3, range ? range->hi : 1.0, ImPlotCond_Always);
  }
  if (!series.empty()) {
    ImPlotSpec spec;
    spec.LineWeight = ui_units(1);  // one pixel at scale 1, two at scale 2, like the style's sizes
    ImPlot::PlotLine(series.label.c_str(), series.t.data(), series.value.data(), static_cast<int>(series.t.size()), spec);
  }
  ImPlot::EndPlot();
}

void draw_render_stats(Document&, EditorState& state) {
  RenderStatsHistory& h = state.stats_history;
  h.record(state.viewport.frame.stats, ImGui::GetTime());
  const bool has_error = !h.estimated_error.empty();
  const float height = std::max(ImGui::GetContentRegionAvail().y, 1.0f);
  if (has_error && ImGui::BeginTable("##stats", 2, ImGuiTableFlags_SizingStretchSame)) {
    // A table cell is padded above and below: without that room the panel would scroll.
    const float cell = std::max(height - 2 * ImGui::GetStyle().CellPadding.y - 1, 1.0f);
    ImGui::TableNextColumn();
    plot_time_series("##spp", h.samples_per_second, false, cell);
    ImGui::TableNextColumn();
    plot_time_series("##error", h.estimated_error, true, cell);
    ImGui::EndTable();
  } else {
    plot_time_series("##spp", h.samples_per_second, false, height);
  }
}

}  // namespace glint
