#include "editor/export_job.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <epoxy/gl.h>

#include "renderer/atomic_file.h"
#include "renderer/gl_context.h"
#include "renderer/gpu_renderer.h"
#include "renderer/image.h"
#include "renderer/render_metadata.h"
#include "renderer/render_output.h"
#include "renderer/render_policy.h"
#include "renderer/render_session.h"
#include "renderer/scene_validation.h"

namespace glint {

std::string validate_export_settings(const ExportSettings& s) {
  // The loader's film limits and message (scene_validation.h): an export renders with a second
  // GpuRenderer of this size, whose GPU buffers the same estimate covers.
  if (const auto problem = check_film_size(s.width, s.height)) {
    const std::string& key = problem->json_path;
    return (key == "film.width" ? "the width " : key == "film.height" ? "the height " : "") +
           problem->problem;
  }
  if (!s.use_time && s.samples < 1) return "samples per pixel must be at least 1";
  if (s.use_time && !(s.seconds > 0 && std::isfinite(s.seconds))) return "the time budget must be positive";
  if (s.output.empty()) return "no output file chosen";
  if (const auto problem = output_format_problem(s.output)) return "the output " + *problem;
  if (s.alpha && s.output.extension() == ".hdr") return "a transparent background needs PNG or EXR (HDR has no alpha)";
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
  // The device's back end, or the compute shader for an image too small for llvmpipe's
  // fragment path to use every thread (the same image; renderer/render_policy.h).
  options.backend = backend_for_image(backend, settings_.width, settings_.height, on_llvmpipe(),
                                      llvmpipe_thread_count())
                        .backend;
  renderer_ = std::make_unique<GpuRenderer>(options);
  RenderOptions estimator = settings_.estimator;
  estimator.transparent_background = settings_.alpha;
  renderer_->set_options(estimator);
  renderer_->set_aovs_enabled(settings_.denoise);
  renderer_->sync(scene_, settings_.width, settings_.height);
  RenderSessionOptions session;
  session.target = settings_.use_time ? RenderTarget{0, settings_.seconds} : RenderTarget{settings_.samples, 0};
  // A pass may take far longer than a UI frame (llvmpipe): in bands that fit the slice.
  session.tiled = true;
  session_ = std::make_unique<RenderSession>(*renderer_, session);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

ExportJob::~ExportJob() = default;

int64_t ExportJob::samples() const { return renderer_ ? renderer_->sample_count() : 0; }

int64_t ExportJob::step_pixel_samples() const {
  return session_ ? session_->step_pixel_samples() : 0;
}

float ExportJob::progress() const {
  if (state_ == State::done) return 1;
  return session_ ? session_->progress() : 0.0f;
}

void ExportJob::cancel() {
  if (denoising_.valid()) {  // the render is done and its file being written: let it finish
    denoising_.wait();
    poll_denoise();
    return;
  }
  if (state_ == State::running) state_ = State::cancelled;
  session_.reset();
  renderer_.reset();  // frees the export-sized buffers now
}

bool ExportJob::step(double slice_seconds) {
  if (state_ != State::running) return false;
  if (denoising_.valid()) {
    poll_denoise();
    return state_ == State::running;
  }
  try {
    // Passes of about a quarter of the slice where they are that fast (fewer passes); slower
    // ones are traced in bands that fit the slice, so the UI gets its frames either way.
    BatchPolicy batch;
    batch.grow_below = slice_seconds * 0.25;
    batch.shrink_above = slice_seconds;
    session_->set_batch_policy(batch);
    session_->step(slice_seconds);
    traced_seconds_ = session_->seconds();
    if (session_->done()) finish();
  } catch (const std::exception& e) {
    state_ = State::failed;
    error_ = e.what();
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return state_ == State::running;
}

void ExportJob::finish() {
  if (!settings_.denoise) {
    // As `glint render` writes: PNG tonemapped with the display settings, HDR/EXR linear, alpha 1
    // or the coverage.
    RenderOutputOptions options;
    options.metadata = render_metadata(scene_, settings_.estimator, renderer_->sample_count());
    options.alpha = settings_.alpha;
    save_render_output(*renderer_, scene_.display, settings_.output, options);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    state_ = State::done;
    return;
  }
  // Read back here (GL), denoise and write on a worker: seconds at full HD on a CPU.
  RenderImages images = read_render_images(*renderer_, settings_.alpha);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  RenderOutputOptions options;
  options.denoise = true;
  options.alpha = settings_.alpha;
  options.metadata = render_metadata(scene_, settings_.estimator, renderer_->sample_count());
  denoising_ = std::async(std::launch::async, [images = std::move(images), display = scene_.display,
                                               output = settings_.output, options = std::move(options)]() {
    const RenderOutputReport report = save_render_images(images, display, output, options);
    if (report.denoise_failed) throw std::runtime_error(report.note);  // the noisy image is written
    if (!report.denoised) return report.note;
    char text[160];
    std::snprintf(text, sizeof text, "denoised (biased) on the %s in %.2f s", report.device.c_str(),
                  report.denoise_seconds);
    return std::string(text);
  });
}

void ExportJob::poll_denoise() {
  if (denoising_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
  try {
    denoise_note_ = denoising_.get();
    state_ = State::done;
  } catch (const std::exception& e) {
    state_ = State::failed;
    error_ = e.what();
  }
}

}  // namespace glint
