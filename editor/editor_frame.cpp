#include "editor/editor_frame.h"

#include <imgui.h>

#include "editor/ui.h"
#include "editor/viewport_renderer.h"

namespace glint {

void editor_frame(Document& doc, EditorState& state, ViewportRenderer& viewport) {
  draw_editor_ui(doc, state);
  state.viewport.frame = viewport.render(doc.scene, viewport_request(state));
  step_export(state, viewport.trace_seconds());
  doc.end_frame(ImGui::IsAnyItemActive() || state.tools.interacting);
  show_viewport_image(state.viewport);
  ImGui::Render();
}

}  // namespace glint
