#include "editor/export_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <epoxy/gl.h>

#include "renderer/atomic_file.h"
#include "renderer/gpu_renderer.h"
#include "renderer/image.h"
#include "renderer/project_file.h"

namespace glint {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

std::string validate_export_settings(const ExportSettings& s) {
  // The loader's film limits and message (project_file.h): an export renders with a second
  // GpuRenderer of this size, whose GPU buffers the same estimate covers.
  if (const auto problem = check_film_size(s.width, s.height)) {
    const std::string& key = problem->json_path;
    return (key == "film.width" ? "the width " : key == "film.height" ? "the height " : "") +
           problem->problem;
  }
  if (!s.use_time && s.samples < 1) return "samples per pixel must be at least 1";
  if (s.use_time && !(s.seconds > 0 && std::isfinite(s.seconds))) return "the time budget must be positive";
  if (s.output.empty()) return "no output file chosen";
  auto ext = s.output.extension().string();
  if (ext != ".png" && ext != ".hdr" && ext != ".exr") return "the output must end in .png, .hdr or .exr";
  auto dir = std::filesystem::absolute(s.output).parent_path();
  if (!std::filesystem::is_directory(dir)) return "the folder " + dir.string() + " does not exist";
  return "";
}

ExportJob::ExportJob(const Scene& scene, ExportSettings settings, std::shared_ptr<ProgramWorker> worker,
                     TraceBackend backend)
    : scene_(scene), settings_(std::move(settings)) {
  if (std::string problem = validate_export_settings(settings_); !problem.empty())
    throw std::runtime_error(problem);
  // Once per export, not in validate_export_settings (which the dialog calls every frame): it
  // creates and removes a file to learn whether the folder is writable.
  if (const auto problem = file_write_problem(settings_.output))
    throw std::runtime_error(settings_.output.string() + ": " + *problem);
  auto errors = validate_scene(scene_);
  if (!errors.empty()) throw std::runtime_error(errors.front().what());
  GpuRendererOptions options;
  options.worker = std::move(worker);
  options.backend = backend;
  renderer_ = std::make_unique<GpuRenderer>(options);
  renderer_->set_options(settings_.estimator);
  renderer_->sync(scene_, settings_.width, settings_.height);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

ExportJob::~ExportJob() = default;

int64_t ExportJob::samples() const { return renderer_ ? renderer_->sample_count() : 0; }

float ExportJob::progress() const {
  if (state_ == State::done) return 1;
  double p = settings_.use_time ? traced_seconds_ / settings_.seconds
                                : double(samples()) / double(settings_.samples);
  return static_cast<float>(std::clamp(p, 0.0, 1.0));
}

void ExportJob::cancel() {
  if (state_ == State::running) state_ = State::cancelled;
  renderer_.reset();  // frees the export-sized buffers now
}

bool ExportJob::step(double slice_seconds) {
  if (state_ != State::running) return false;
  try {
    auto start = std::chrono::steady_clock::now();
    do {
      bool target_reached = settings_.use_time
                                ? traced_seconds_ >= settings_.seconds && samples() > 0
                                : samples() >= settings_.samples;
      if (target_reached) {
        finish();
        break;
      }
      int k = batch_;
      if (!settings_.use_time) k = static_cast<int>(std::min<int64_t>(k, settings_.samples - samples()));
      auto pass = std::chrono::steady_clock::now();
      renderer_->trace(k);
      glFinish();  // measure the real pass time (and keep passes from queueing up)
      double t = seconds_since(pass);
      traced_seconds_ += t;
      // Passes about a quarter of the slice: fewer passes, yet the UI gets its frames.
      if (t < slice_seconds * 0.25 && batch_ < 1024) batch_ *= 2;
      else if (t > slice_seconds && batch_ > 1) batch_ /= 2;
    } while (seconds_since(start) < slice_seconds);
  } catch (const std::exception& e) {
    state_ = State::failed;
    error_ = e.what();
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return state_ == State::running;
}

void ExportJob::finish() {
  // As `glint render` writes: PNG tonemapped with the display settings, HDR/EXR linear, alpha 1.
  save_render(*renderer_, settings_.output);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  state_ = State::done;
}

}  // namespace glint
