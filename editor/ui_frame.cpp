// One frame of the editor's UI: the menu bar, the status bar, and the panels in the dock space
// (editor/ui_layout.h).
#include <cstdio>

#include <imgui_internal.h>  // BeginViewportSideBar: a bar that shrinks the dock space's area

#include "editor/ui.h"
#include "editor/ui_layout.h"

namespace glint {

std::vector<StatusPiece> status_line(const EditorState& state, double now_s) {
  const FrameStats& s = state.viewport.frame.stats;
  char text[512];
  int n = std::snprintf(text, sizeof text, "%lld spp   %.1f spp/s   %.1f ms/frame   %dx%d",
                        static_cast<long long>(s.spp), s.spp_per_second, s.ms_per_frame, s.trace_width,
                        s.trace_height);
  // Without a reference: from the pixels' sample variance (renderer/error_estimate.h).
  if (s.estimated_relmse >= 0)
    n += std::snprintf(text + n, sizeof text - n, "   est. relMSE %.2e", s.estimated_relmse);
  if (s.target_reached)
    n += std::snprintf(text + n, sizeof text - n, " (target %.2e reached: paused)", state.viewport.target_error);
  float full_w = state.viewport.size.x * state.viewport.framebuffer_scale;
  if (s.trace_width > 0 && full_w > s.trace_width * 1.5f)
    n += std::snprintf(text + n, sizeof text - n, " (preview 1/%d)", int(full_w / s.trace_width + 0.5f));
  n += std::snprintf(text + n, sizeof text - n, "   %s", s.gl_renderer.c_str());
  if (!s.denoise_status.empty() && n < int(sizeof text))
    std::snprintf(text + n, sizeof text - n, "   %s", s.denoise_status.c_str());
  std::vector<StatusPiece> pieces{{text, ImGui::GetStyleColorVec4(ImGuiCol_Text)}};
  if (state.autosave && !state.autosave->last_error().empty())
    pieces.push_back({"  |  autosave failed: " + state.autosave->last_error(), ImVec4(1, 0.45f, 0.4f, 1)});
  if (!state.messages.note.empty() && now_s < state.messages.note_until)
    pieces.push_back({"  |  " + state.messages.note, ImVec4(1, 0.6f, 0.3f, 1)});
  if (!state.messages.message.empty() && now_s < state.messages.message_until) {
    pieces.push_back({"  |  " + state.messages.message, ImVec4(1, 0.85f, 0.4f, 1)});
  } else if (export_running(state)) {
    std::snprintf(text, sizeof text, "  |  exporting %.0f%%", state.export_ui.job->progress() * 100);
    pieces.push_back({text, ImVec4(0.5f, 0.9f, 1, 1)});
  }
  return pieces;
}

void draw_status_bar(Document&, EditorState& state) {
  const std::vector<StatusPiece> pieces = status_line(state, ImGui::GetTime());
  for (size_t i = 0; i < pieces.size(); ++i) {
    if (i > 0) ImGui::SameLine(0, 0);
    ImGui::PushStyleColor(ImGuiCol_Text, pieces[i].color);
    ImGui::TextUnformatted(pieces[i].text.c_str());
    ImGui::PopStyleColor();
  }
}

void draw_editor_ui(Document& doc, EditorState& state) {
  ImGuiIO& io = ImGui::GetIO();
  state.viewport.framebuffer_scale = io.DisplayFramebufferScale.x > 0 ? io.DisplayFramebufferScale.x : 1.0f;
  state.tools.interacting = false;
  state.tools.navigated = false;

  handle_shortcuts(doc, state);
  draw_main_menu(doc, state);

  // The status bar takes the bottom of the work area; the dock space fills the rest.
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8 * state.content_scale, 3 * state.content_scale));
  if (ImGui::BeginViewportSideBar("##status", ImGui::GetMainViewport(), ImGuiDir_Down,
                                  ImGui::GetFrameHeight(), ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoSavedSettings))
    draw_status_bar(doc, state);
  ImGui::End();
  ImGui::PopStyleVar();
  dock_panels(state.content_scale);

  if (ImGui::Begin(kOutlinerWindow)) draw_outliner(doc, state);
  ImGui::End();
  if (ImGui::Begin(kPropertiesWindow)) draw_properties(doc, state);
  ImGui::End();
  if (ImGui::Begin(kStatsWindow)) draw_render_stats(doc, state);
  ImGui::End();

  draw_viewport(doc, state);
  draw_export_dialog(doc, state);
  draw_document_modals(doc, state);
  draw_recovery_offer(doc, state);
}

}  // namespace glint
