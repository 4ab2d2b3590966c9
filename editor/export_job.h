// Export of a final render from the editor, without blocking it: a second GpuRenderer at the
// export size and a RenderSession that traces one slice per call of step(), so the UI keeps
// running between slices. A pass longer than a slice is traced in bands of rows over several
// slices (RenderSessionOptions::tiled), with the same image as in one go.
// No ImGui here (ui_export.cpp is its dialog); needs a current OpenGL 4.5 context.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <future>
#include <memory>
#include <string>

#include "renderer/render_options.h"
#include "renderer/scene.h"
#include "renderer/stopwatch.h"
#include "renderer/trace_backend.h"

namespace glint {

class GpuRenderer;
class ProgramWorker;
class RenderSession;

struct ExportSettings {
  int width = 960;
  int height = 540;
  bool use_time = false;   // false: stop at `samples`; true: stop after `seconds` of tracing
  int64_t samples = 64;
  double seconds = 10;
  std::filesystem::path output;  // .png (tonemapped), .hdr or .exr (linear radiance, alpha 1)
  RenderOptions estimator;        // the viewport's (set when the export starts)
  // Denoise the output (renderer/render_output.h; biased): on a worker thread once the target
  // is reached, so the UI keeps running; an EXR keeps the noisy colour as a layer.
  bool denoise = false;
  // Set by the dialog's "Viewport aspect": the viewport's size (any unit) whose whole view the
  // export frames, margins around the film included (editor/film_frame.h). Applies while the
  // export's size has that aspect; {0, 0}: the film's framing.
  float viewport_w = 0, viewport_h = 0;
  // A transparent background (RenderOutputOptions::alpha): PNG or EXR only.
  bool alpha = false;
};

// "" when valid, else the problem (shown in the dialog before starting). The size has the
// limits of a project's film (check_film_size, with its GPU memory estimate).
std::string validate_export_settings(const ExportSettings& settings);

class ExportJob {
 public:
  enum class State { running, done, cancelled, failed };

  // Copies the scene; creates the renderer and uploads the scene. Throws on a bad scene/setting
  // and, before rendering, when the output cannot be written (file_write_problem).
  // `worker` (may be null) builds the specialised trace program off the UI thread. `backend` is
  // the device's; an image too small for it on llvmpipe takes the compute shader
  // (backend_for_image).
  ExportJob(const Scene& scene, ExportSettings settings, std::shared_ptr<ProgramWorker> worker = nullptr,
            TraceBackend backend = TraceBackend::fragment);
  ~ExportJob();
  ExportJob(const ExportJob&) = delete;
  ExportJob& operator=(const ExportJob&) = delete;

  // Traces for about `slice_seconds` (at least one band of rows of a pass) and writes the file
  // when the target is reached. Leaves the default framebuffer bound. Returns true while still
  // running.
  bool step(double slice_seconds);
  // Pixel-samples the last step traced (RenderSession::step_pixel_samples).
  int64_t step_pixel_samples() const;
  void cancel();

  State state() const { return state_; }
  float progress() const;  // 0..1
  int64_t samples() const;
  double elapsed_seconds() const { return traced_seconds_; }  // of tracing (what --time counts)
  // Wall-clock seconds since the job started: what the user waits, the UI's frames included
  // (the dialog's time and its time left use it).
  double wall_seconds() const {
    return seconds_since(started_);
  }
  const std::string& error() const { return error_; }
  // When done: how the output was denoised (or why it was not), "" without denoising.
  const std::string& denoise_note() const { return denoise_note_; }
  const ExportSettings& settings() const { return settings_; }

 private:
  void finish();
  void poll_denoise();

  Scene scene_;
  ExportSettings settings_;
  std::unique_ptr<GpuRenderer> renderer_;
  std::unique_ptr<RenderSession> session_;  // traces into renderer_
  State state_ = State::running;
  std::string error_;
  double traced_seconds_ = 0;
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
  std::future<std::string> denoising_;  // the worker's note, once the file is written
  std::string denoise_note_;
};

}  // namespace glint
