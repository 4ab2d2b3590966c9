#include "editor/viewport_denoiser.h"

#include <chrono>
#include <cstdio>
#include <vector>

#include <epoxy/gl.h>

#include "renderer/denoiser.h"
#include "renderer/gpu_renderer.h"
#include "renderer/render_output.h"
#include "renderer/stopwatch.h"

namespace glint {

// The thread starts once every member (its mutex above all) is constructed.
ViewportDenoiser::ViewportDenoiser() { worker_ = std::thread([this] { run_worker(); }); }

ViewportDenoiser::~ViewportDenoiser() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  worker_.join();
  if (texture_) glDeleteTextures(1, &texture_);
}

void ViewportDenoiser::run_worker() {
  for (;;) {
    Job job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || job_.has_value(); });
      if (stop_) return;
      job = std::move(*job_);
      job_.reset();
    }
    Result result;
    result.samples = job.samples;
    result.generation = job.generation;
    try {
      // The fast quality: a preview, redone every few frames.
      if (!denoiser_) denoiser_ = std::make_unique<Denoiser>(DenoiseQuality::fast);
      const auto start = std::chrono::steady_clock::now();
      result.display = tonemapped(denoiser_->denoise(job.colour, &job.albedo, &job.normal), job.display);
      result.seconds = seconds_since(start);
    } catch (const std::exception& e) {
      result.error = e.what();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (denoiser_) device_ = denoiser_->device_name();
    result_ = std::move(result);
    busy_ = false;
  }
}

unsigned ViewportDenoiser::update(GpuRenderer& renderer, const DisplaySettings& display, bool enabled) {
  const int64_t samples = renderer.sample_count();
  if (samples < last_samples_ || (samples == 0 && last_samples_ != 0)) {
    ++generation_;  // the accumulation restarted: older results are of another image
    shown_ = false;
  }
  last_samples_ = samples;
  if (!enabled) {
    if (renderer.aovs_enabled()) renderer.set_aovs_enabled(false);
    shown_ = false;
    status_.clear();
    return 0;
  }
  if (!denoising_available_or_warn_once("glint editor")) {
    status_ = "denoising unavailable: " + *denoising_unavailable();
    return 0;
  }
  if (!renderer.aovs_enabled()) {
    // The AOVs start now: they hold fewer samples than the colour until the next restart,
    // which only makes them noisier.
    renderer.set_aovs_enabled(true);
    frames_since_job_ = 0;
  }
  std::optional<Result> result;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (result_) result.swap(result_);
  }
  if (result && !result->error.empty()) {
    status_ = "denoising failed: " + result->error;
  } else if (result && result->generation == generation_) {
    const Image& img = result->display;
    if (!texture_ || texture_w_ != img.width || texture_h_ != img.height) {
      if (texture_) glDeleteTextures(1, &texture_);
      glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
      glTextureStorage2D(texture_, 1, GL_RGBA8, img.width, img.height);
      glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      texture_w_ = img.width;
      texture_h_ = img.height;
    }
    glTextureSubImage2D(texture_, 0, 0, 0, img.width, img.height, GL_RGBA, GL_FLOAT, img.pixels.data());
    shown_ = true;
    char text[128];
    std::snprintf(text, sizeof text, "denoised (biased) at %lld spp on the %s in %.0f ms",
                  static_cast<long long>(result->samples), device_.c_str(), result->seconds * 1e3);
    status_ = text;
  }
  // A new job every few frames, when the worker is idle and there is something new to show.
  ++frames_since_job_;
  bool idle;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    idle = !busy_ && !job_;
  }
  const bool news = samples != job_samples_ || generation_ != job_generation_;
  const bool due = !shown_ || frames_since_job_ >= kFramesBetween;
  if (idle && samples > 0 && news && due && renderer.width() > 0) {
    Job job;
    job.colour = render_colour(renderer);
    AovImages aovs = renderer.read_aovs();
    job.albedo = std::move(aovs.albedo);
    job.normal = std::move(aovs.normal);
    job.display = display;
    job.samples = samples;
    job.generation = generation_;
    frames_since_job_ = 0;
    job_samples_ = samples;
    job_generation_ = generation_;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      job_ = std::move(job);
      busy_ = true;
    }
    wake_.notify_one();
    if (!shown_) status_ = "denoising...";
  }
  // The denoised image only while it matches the accumulation's size.
  return shown_ && texture_w_ == renderer.width() && texture_h_ == renderer.height() ? texture_ : 0;
}

}  // namespace glint
