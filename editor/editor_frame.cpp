#include "editor/editor_frame.h"

#include <chrono>

#include <imgui.h>

#include "editor/ui.h"
#include "editor/viewport_renderer.h"
#include "renderer/stopwatch.h"

namespace glint {

void editor_frame(Document& doc, EditorState& state, ViewportRenderer& viewport) {
  draw_editor_ui(doc, state);
  state.viewport.frame = viewport.render(doc.scene, viewport_request(state));
  const auto export_start = std::chrono::steady_clock::now();
  step_export(state, viewport.export_slice_seconds());
  viewport.add_trace_seconds(seconds_since(export_start));
  doc.end_frame(ImGui::IsAnyItemActive() || state.tools.interacting, state.tools.navigated);
  show_viewport_image(state.viewport);
  ImGui::Render();
}

void editor_frame_before_viewport(Document& doc, EditorState& state) {
  draw_editor_ui(doc, state);
  doc.end_frame(ImGui::IsAnyItemActive() || state.tools.interacting);
  show_viewport_image(state.viewport);
  ImGui::Render();
}

}  // namespace glint
