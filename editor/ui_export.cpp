// The export dialog: size, samples or time, format; progress bar and cancel while it runs.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "editor/film_frame.h"
#include "editor/ui.h"
#include "editor/ui_context.h"
#include "editor/ui_tip.h"

namespace glint {

ExportSettings default_export_settings(const Document& doc, const EditorState& state) {
  ExportSettings s;
  // The remembered folder, else Pictures or home: beside the project would often be inside a
  // source repository, where a render does not belong.
  std::filesystem::path dir = state.settings.export_dir;
  std::error_code ec;
  if (dir.empty() || !std::filesystem::is_directory(dir, ec)) dir = default_export_dir();
  s.output = dir / (doc.path().empty() ? std::string("render.png") : doc.path().stem().string() + ".png");
  s.width = doc.scene.film.width;
  s.height = doc.scene.film.height;
  return s;
}

void use_viewport_aspect(ExportSettings& s, const ViewportView& view) {
  const float w = std::max(1.0f, view.size.x), h = std::max(1.0f, view.size.y);
  s.height = std::clamp(int(s.width * h / w + 0.5f), 1, 16384);
  s.viewport_w = w;
  s.viewport_h = h;
}

// Whether the size still has the aspect "Viewport aspect" gave it (to its rounding).
static bool frames_viewport(const ExportSettings& s) {
  if (!(s.viewport_w > 0) || !(s.viewport_h > 0)) return false;
  return std::abs(int(s.width * s.viewport_h / s.viewport_w + 0.5f) - s.height) <= 1;
}

Scene export_scene(const Scene& scene, const ExportSettings& s) {
  Scene out = scene;
  if (frames_viewport(s)) out.camera = viewport_camera(scene.camera, {s.viewport_w, s.viewport_h}, scene.film);
  return out;
}

std::string export_eta(double progress, double elapsed_seconds) {
  if (!(progress > 0.01) || !(elapsed_seconds > 0.5)) return "estimating time left";
  const double left = elapsed_seconds * (1 - progress) / progress;
  char text[64];
  if (left < 60) std::snprintf(text, sizeof text, "about %.0f s left", std::ceil(left));
  else if (left < 3600) std::snprintf(text, sizeof text, "about %d min %02d s left", int(left) / 60, int(left) % 60);
  else std::snprintf(text, sizeof text, "about %d h %02d min left", int(left) / 3600, int(left) / 60 % 60);
  return text;
}

bool export_running(const EditorState& state) {
  return state.export_ui.job && state.export_ui.job->state() == ExportJob::State::running;
}

void step_export(EditorState& state, double slice_seconds) {
  if (!export_running(state)) return;
  state.export_ui.job->step(slice_seconds);
  switch (state.export_ui.job->state()) {
    case ExportJob::State::done: {
      // What it reached: a time-limited export stops at as many samples as fitted.
      const ExportJob& job = *state.export_ui.job;
      char reached[96];
      std::snprintf(reached, sizeof reached, " (%lld spp in %.1f s)", static_cast<long long>(job.samples()),
                    job.wall_seconds());
      state.export_ui.message = "Wrote " + job.settings().output.string() + reached;
      if (!state.export_ui.job->denoise_note().empty())
        state.export_ui.message += " (" + state.export_ui.job->denoise_note() + ")";
      show_message(state, state.export_ui.message);
      break;
    }
    case ExportJob::State::failed:
      state.export_ui.message = "Export failed: " + state.export_ui.job->error();
      show_error(state, state.export_ui.message);
      break;
    default: break;
  }
}

// Size: typed, the film's, or the viewport's aspect (which also frames its margins).
static void draw_export_size(ExportSettings& s, const Document& doc, const EditorState& state) {
  int size[2] = {s.width, s.height};
  if (ImGui::InputInt2("Size (pixels)", size)) {
    s.width = std::clamp(size[0], 1, 16384);
    s.height = std::clamp(size[1], 1, 16384);
  }
  tip("Width and height of the image in pixels (1 to 16384 each).");
  if (ImGui::SmallButton("Film size")) {
    s.width = doc.scene.film.width;
    s.height = doc.scene.film.height;
    s.viewport_w = s.viewport_h = 0;
  }
  tip("The film's size (Camera > Film size): exactly what the viewport's frame shows.");
  ImGui::SameLine();
  if (ImGui::SmallButton("Viewport aspect")) use_viewport_aspect(s, state.viewport);
  tip("Keep the width; set the height to the viewport panel's aspect and frame all it shows.");
  if (frames_viewport(s))
    ImGui::TextColored(ImVec4(0.6f, 0.85f, 1, 1), "Frames the whole viewport, margins included.");
  else if (int64_t(s.width) * doc.scene.film.height != int64_t(s.height) * doc.scene.film.width)
    ImGui::TextColored(ImVec4(1, 0.8f, 0.4f, 1), "Not the film's aspect (%dx%d): the viewport's frame shows the film.",
                       doc.scene.film.width, doc.scene.film.height);
}

// When it stops: after a number of samples per pixel or after a time.
static void draw_export_budget(ExportSettings& s) {
  int budget = s.use_time ? 1 : 0;
  ImGui::RadioButton("Samples", &budget, 0);
  tip("Stop after a number of samples per pixel.");
  ImGui::SameLine();
  ImGui::RadioButton("Time", &budget, 1);
  tip("Stop after a time: as many samples as fit (more on a faster machine).");
  s.use_time = budget == 1;
  if (s.use_time) {
    float seconds = static_cast<float>(s.seconds);
    if (ImGui::DragFloat("Seconds", &seconds, 0.5f, 0.1f, 86400, "%.1f s", ImGuiSliderFlags_AlwaysClamp))
      s.seconds = seconds;
    tip("How long to render, in seconds.");
  } else {
    int spp = static_cast<int>(std::min<int64_t>(s.samples, 1 << 30));
    if (ImGui::InputInt("Samples/pixel", &spp)) s.samples = std::max(1, spp);
    tip("Samples per pixel: the noise (standard deviation) falls as one over its square root.");
  }
}

// The file, its format (the extension) and what goes into it.
static void draw_export_output(ExportSettings& s, Document& doc, EditorState& state) {
  char path[1024];
  std::snprintf(path, sizeof path, "%s", s.output.string().c_str());
  if (ImGui::InputText("Output file", path, sizeof path)) s.output = path;
  tip("Where the image is written; its extension picks the format.");
  static const char* const kFormats[] = {".png", ".hdr", ".exr"};
  int format = 0;
  for (int i = 0; i < 3; ++i)
    if (s.output.extension() == kFormats[i]) format = i;
  if (ImGui::Combo("Format", &format, "PNG (tonemapped)\0HDR (linear)\0EXR (linear float)\0")) s.output.replace_extension(kFormats[format]);
  tip("PNG: 8-bit, with the display's exposure and tonemap. HDR, EXR: the linear radiance\n"
      "(EXR as 32-bit floats), for further processing.");
  if (ImGui::SmallButton("Choose file...")) choose_file(doc, state, FilePurpose::export_output);
  tip("Choose the output file in a file dialog.");
  ImGui::Checkbox("Denoise (biased; EXR keeps the noisy layer)", &s.denoise);
  tip("Filter the noise with Open Image Denoise: smoother, but detail may blur (biased).");
  ImGui::Checkbox("Transparent background (PNG, EXR)", &s.alpha);
  tip("Alpha is each pixel's coverage: 0 where the environment shows, fractional on edges,\n"
      "for compositing (the environment still lights the scene; EXR premultiplied).");
}

// A running export: time left, progress (samples and seconds so far) and Cancel.
static void draw_export_progress(EditorState& state) {
  ExportJob& job = *state.export_ui.job;
  ExportUi& ui = state.export_ui;
  // The time left above the bar: the bar's hover help opens below it.
  ImGui::TextUnformatted(export_eta(job.progress(), job.wall_seconds()).c_str());
  ui.time_left_min = ImGui::GetItemRectMin();
  ui.time_left_max = ImGui::GetItemRectMax();
  char overlay[96];
  std::snprintf(overlay, sizeof overlay, "%.0f%%: %lld spp, %.1f s", job.progress() * 100,
                static_cast<long long>(job.samples()), job.wall_seconds());
  ImGui::ProgressBar(job.progress(), ImVec2(-1, 0), overlay);
  ui.progress_min = ImGui::GetItemRectMin();
  ui.progress_max = ImGui::GetItemRectMax();
  if (ImGui::IsItemHovered()) {
    ImGui::SetNextWindowPos(ImVec2(ui.progress_min.x, ui.progress_max.y + ImGui::GetStyle().ItemSpacing.y));
    ImGui::SetTooltip("Done so far: samples per pixel and seconds; the viewport pauses while it runs.");
  }
  if (ImGui::Button("Cancel", ImVec2(ui_units(120), 0))) {
    job.cancel();
    ui.message = "Export cancelled";
  }
  tip("Stop the export.");
}

// Render (disabled while the settings have a problem) and the last export's result.
static void draw_export_start(Document& doc, EditorState& state, const std::string& problem) {
  ExportSettings& s = state.export_ui.settings;
  ImGui::BeginDisabled(!problem.empty());
  if (ImGui::Button("Render", ImVec2(ui_units(120), 0))) {
    try {
      s.estimator = state.viewport.estimator;
      state.export_ui.job =
          std::make_unique<ExportJob>(export_scene(doc.scene, s), s, state.shader_worker, state.trace_backend);
      state.export_ui.message.clear();
      const std::filesystem::path folder = std::filesystem::absolute(s.output).parent_path();
      if (state.settings.export_dir != folder) {  // remembered for the next session
        state.settings.export_dir = folder;
        settings_changed(state);
      }
    } catch (const std::exception& e) {
      show_error(state, std::string("Cannot export: ") + e.what());
    }
  }
  tip("Render the scene with these settings and write the file (the viewport pauses meanwhile).");
  ImGui::EndDisabled();
  if (!state.export_ui.message.empty()) ImGui::TextWrapped("%s", state.export_ui.message.c_str());
}

void draw_export_dialog(Document& doc, EditorState& state) {
  if (!state.export_ui.show) return;
  ExportSettings& s = state.export_ui.settings;
  if (s.output.empty()) s = default_export_settings(doc, state);
  // Auto-sized: the settings, the progress with its ETA, Cancel and the result always show
  // without scrolling.
  ImGui::SetNextWindowSizeConstraints(ImVec2(ui_units(520), 0), ImVec2(FLT_MAX, FLT_MAX));
  ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x * 0.5f, ImGui::GetIO().DisplaySize.y * 0.35f),
                          ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (!ImGui::Begin("Export render", &state.export_ui.show,
                    ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::End();
    return;
  }
  const bool running = export_running(state);
  ImGui::BeginDisabled(running);
  ImGui::PushItemWidth(-ui_units(130));
  draw_export_size(s, doc, state);
  draw_export_budget(s);
  draw_export_output(s, doc, state);
  ImGui::PopItemWidth();
  ImGui::EndDisabled();

  const std::string problem = validate_export_settings(s);
  if (!problem.empty() && !running) ImGui::TextColored(ImVec4(1, 0.5f, 0.4f, 1), "%s", problem.c_str());
  ImGui::Separator();
  if (running) draw_export_progress(state);
  else draw_export_start(doc, state, problem);
  ImGui::End();
}

}  // namespace glint
