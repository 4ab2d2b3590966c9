// One frame of the editor's UI: the menu bar, the status bar, and the panels in the dock space
// (editor/ui_layout.h).
#include <cstdio>

#include <imgui_internal.h>  // BeginViewportSideBar: a bar that shrinks the dock space's area

#include "editor/ui.h"
#include "editor/ui_layout.h"

namespace glint {

namespace {

// The viewport's figures, each through `figure(priority, format, ...)`.
template <class Figure>
void status_figures(const EditorState& state, Figure&& figure) {
  const FrameStats& s = state.viewport.frame.stats;
  figure(0, "%lld spp", static_cast<long long>(s.spp));
  figure(4, "%.1f spp/s", s.spp_per_second);
  figure(3, "%.1f ms/frame", s.ms_per_frame);
  figure(2, "%dx%d", s.trace_width, s.trace_height);
  float full_w = state.viewport.size.x * state.viewport.framebuffer_scale;
  if (s.trace_width > 0 && full_w > s.trace_width * 1.5f)
    figure(2, "(preview 1/%d)", int(full_w / s.trace_width + 0.5f));
  if (s.pass_progress > 0) figure(2, "(pass %.0f%%)", s.pass_progress * 100);
  // Without a reference: from the pixels' sample variance (renderer/error_estimate.h).
  if (s.estimated_relmse >= 0) figure(3, "est. relMSE %.2e", s.estimated_relmse);
  if (s.target_reached) figure(1, "(target %.2e reached: paused)", state.viewport.target_error);
  figure(6, "%s", s.gl_renderer.c_str());
  if (!s.denoise_status.empty()) figure(5, "%s", s.denoise_status.c_str());
}

}  // namespace

std::vector<StatusPiece> status_line(const EditorState& state, double now_s) {
  const FrameStats& s = state.viewport.frame.stats;
  const ImVec4 plain = ImGui::GetStyleColorVec4(ImGuiCol_Text);
  std::vector<StatusPiece> pieces;
  // Figures first in the line, each with its own separator and its importance (0 first kept).
  auto figure = [&](int priority, const char* format, auto... args) {
    char text[256];
    std::snprintf(text, sizeof text, format, args...);
    pieces.push_back({(pieces.empty() ? "" : "   ") + std::string(text), plain, priority});
  };
  if (!state.viewport.frame.display_texture && s.scene_problem.empty() && s.trace_width == 0) {
    figure(0, "%s", kCompilingShaders);  // no figures before the first image
  } else {
    status_figures(state, figure);
  }
  if (state.autosave && !state.autosave->last_error().empty())
    pieces.push_back({"  |  autosave failed: " + state.autosave->last_error(), ImVec4(1, 0.45f, 0.4f, 1), 0});
  if (!state.messages.note.empty() && now_s < state.messages.note_until)
    pieces.push_back({"  |  " + state.messages.note, ImVec4(1, 0.6f, 0.3f, 1), 1});
  if (!state.messages.message.empty() && now_s < state.messages.message_until) {
    pieces.push_back({"  |  " + state.messages.message, ImVec4(1, 0.85f, 0.4f, 1), 0});
  } else if (export_running(state)) {
    char text[64];
    std::snprintf(text, sizeof text, "  |  exporting %.0f%%", state.export_ui.job->progress() * 100);
    pieces.push_back({text, ImVec4(0.5f, 0.9f, 1, 1), 0});
  }
  return pieces;
}

void draw_status_bar(Document&, EditorState& state) {
  const float width = ImGui::GetContentRegionAvail().x;
  const std::vector<StatusPiece> pieces = fit_status_line(status_line(state, ImGui::GetTime()), width);
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
