// The viewport's Denoise toggle (docs/DESIGN.md, Denoising): every few frames the current
// accumulation and its auxiliary images are read back and denoised on a worker thread, and the
// newest result is shown instead of the noisy image while the accumulation goes on underneath.
// A result is dropped if the accumulation restarted after its read-back (an edit, a camera
// move): then the noisy image shows until the next one. Denoising is biased: the preview only.
// Needs a current OpenGL context on the calling thread; the worker touches no GL.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "renderer/image.h"
#include "renderer/scene.h"

namespace glint {

class Denoiser;
class GpuRenderer;

class ViewportDenoiser {
 public:
  ViewportDenoiser();
  ~ViewportDenoiser();  // joins the worker
  ViewportDenoiser(const ViewportDenoiser&) = delete;
  ViewportDenoiser& operator=(const ViewportDenoiser&) = delete;

  // Once per frame after the trace. Returns the texture to show: the denoised image of this
  // accumulation when one is ready, else 0 (show the renderer's own). `enabled` false stops
  // reading back and turns the renderer's AOVs off again.
  unsigned update(GpuRenderer& renderer, const DisplaySettings& display, bool enabled);

  // "denoised at N spp on the CPU", "denoising ...", or why it is unavailable.
  const std::string& status() const { return status_; }

  // Frames between read-backs (the worker must also be idle).
  static constexpr int kFramesBetween = 8;

 private:
  struct Job {
    Image colour, albedo, normal;
    DisplaySettings display;
    int64_t samples = 0;
    uint64_t generation = 0;
  };
  struct Result {
    Image display;  // tonemapped RGBA in [0,1]
    int64_t samples = 0;
    uint64_t generation = 0;
    double seconds = 0;
    std::string error;
  };
  void run_worker();

  std::thread worker_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<Job> job_;        // waiting for the worker
  std::optional<Result> result_;  // waiting for the UI thread
  bool busy_ = false, stop_ = false;
  std::unique_ptr<Denoiser> denoiser_;  // made and used on the worker only
  std::string device_;

  // UI thread only.
  uint64_t generation_ = 0;      // counts accumulation restarts seen
  int64_t last_samples_ = -1;    // the accumulation's count at the last frame
  int frames_since_job_ = 0;
  int64_t job_samples_ = -1;     // the accumulation's count at the last read-back
  uint64_t job_generation_ = 0;
  bool shown_ = false;           // texture_ holds a result of this generation
  unsigned texture_ = 0;
  int texture_w_ = 0, texture_h_ = 0;
  std::string status_;
};

}  // namespace glint
