// The export dialog: size, samples or time, format; progress bar and cancel while it runs.
#include <cstdio>
#include <cstring>

#include "editor/ui.h"
#include "editor/ui_context.h"

namespace glint {

bool export_running(const EditorState& state) {
  return state.export_ui.job && state.export_ui.job->state() == ExportJob::State::running;
}

void step_export(EditorState& state, double slice_seconds) {
  if (!export_running(state)) return;
  state.export_ui.job->step(slice_seconds);
  switch (state.export_ui.job->state()) {
    case ExportJob::State::done:
      state.export_ui.message = "Wrote " + state.export_ui.job->settings().output.string();
      show_message(state, state.export_ui.message);
      break;
    case ExportJob::State::failed:
      state.export_ui.message = "Export failed: " + state.export_ui.job->error();
      show_error(state, state.export_ui.message);
      break;
    default: break;
  }
}

void draw_export_dialog(Document& doc, EditorState& state) {
  if (!state.export_ui.show) return;
  ExportSettings& s = state.export_ui.settings;
  if (s.output.empty()) {
    // A first guess beside the project, named after it.
    auto dir = doc.path().empty() ? std::filesystem::current_path() : doc.path().parent_path();
    s.output = dir / (doc.path().empty() ? std::string("render.png") : doc.path().stem().string() + ".png");
    s.width = doc.scene.film.width;
    s.height = doc.scene.film.height;
  }
  ImGui::SetNextWindowSize(ImVec2(ui_units(460), 0), ImGuiCond_Appearing);
  ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x * 0.5f, ImGui::GetIO().DisplaySize.y * 0.35f),
                          ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (!ImGui::Begin("Export render", &state.export_ui.show, ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoCollapse)) {
    ImGui::End();
    return;
  }
  const bool running = export_running(state);
  ImGui::BeginDisabled(running);
  ImGui::PushItemWidth(-ui_units(130));
  int size[2] = {s.width, s.height};
  if (ImGui::InputInt2("Size (pixels)", size)) {
    s.width = std::clamp(size[0], 1, 16384);
    s.height = std::clamp(size[1], 1, 16384);
  }
  if (ImGui::SmallButton("Film size")) {
    s.width = doc.scene.film.width;
    s.height = doc.scene.film.height;
  }
  ImGui::SameLine();
  if (ImGui::SmallButton("Viewport aspect")) {
    s.height = std::max(1, int(s.width * state.viewport.size.y / std::max(1.0f, state.viewport.size.x) + 0.5f));
  }
  int budget = s.use_time ? 1 : 0;
  ImGui::RadioButton("Samples", &budget, 0);
  ImGui::SameLine();
  ImGui::RadioButton("Time", &budget, 1);
  s.use_time = budget == 1;
  if (s.use_time) {
    float seconds = static_cast<float>(s.seconds);
    if (ImGui::DragFloat("Seconds", &seconds, 0.5f, 0.1f, 86400, "%.1f s", ImGuiSliderFlags_AlwaysClamp))
      s.seconds = seconds;
  } else {
    int spp = static_cast<int>(std::min<int64_t>(s.samples, 1 << 30));
    if (ImGui::InputInt("Samples/pixel", &spp)) s.samples = std::max(1, spp);
  }
  char path[1024];
  std::snprintf(path, sizeof path, "%s", s.output.string().c_str());
  if (ImGui::InputText("Output file", path, sizeof path)) s.output = path;
  static const char* const kFormats[] = {".png", ".hdr", ".exr"};
  int format = 0;
  for (int i = 0; i < 3; ++i)
    if (s.output.extension() == kFormats[i]) format = i;
  if (ImGui::Combo("Format", &format, "PNG (tonemapped)\0HDR (linear)\0EXR (linear float)\0")) s.output.replace_extension(kFormats[format]);
  if (ImGui::SmallButton("Choose file...")) choose_file(doc, state, FilePurpose::export_output);
  ImGui::PopItemWidth();
  ImGui::EndDisabled();

  std::string problem = validate_export_settings(s);
  if (!problem.empty() && !running) ImGui::TextColored(ImVec4(1, 0.5f, 0.4f, 1), "%s", problem.c_str());
  ImGui::Separator();
  if (running) {
    ExportJob& job = *state.export_ui.job;
    char overlay[96];
    std::snprintf(overlay, sizeof overlay, "%lld spp, %.1f s", static_cast<long long>(job.samples()),
                  job.elapsed_seconds());
    ImGui::ProgressBar(job.progress(), ImVec2(-1, 0), overlay);
    if (ImGui::Button("Cancel", ImVec2(ui_units(120), 0))) {
      job.cancel();
      state.export_ui.message = "Export cancelled";
    }
  } else {
    ImGui::BeginDisabled(!problem.empty());
    if (ImGui::Button("Render", ImVec2(ui_units(120), 0))) {
      try {
        s.estimator = state.viewport.estimator;
        state.export_ui.job = std::make_unique<ExportJob>(doc.scene, s, state.shader_worker, state.trace_backend);
        state.export_ui.message.clear();
      } catch (const std::exception& e) {
        show_error(state, std::string("Cannot export: ") + e.what());
      }
    }
    ImGui::EndDisabled();
    if (!state.export_ui.message.empty()) ImGui::TextWrapped("%s", state.export_ui.message.c_str());
  }
  ImGui::End();
}

}  // namespace glint
