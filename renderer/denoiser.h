// Denoising with Intel Open Image Denoise 2.x (docs/DESIGN.md, Denoising): its "RT" filter on
// the linear colour, guided by the albedo and normal images of renderer/aov_pass.h. The library
// is loaded at run time (renderer/oidn_api.h): next to the executable (where the build puts
// it, cmake/OpenImageDenoise.cmake), in $GLINT_OIDN_DIR, or on the loader's path. Without it
// everything else works and denoising_unavailable() says why.
//
// Denoising is BIASED: it trades noise for blur and artefacts that no sample count removes. It
// is never used for references or for the true error of a convergence log.
#pragma once

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "renderer/image.h"

namespace glint {

struct DenoiseError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Why the library cannot be used (not found, a symbol missing, not x86_64 Linux), or nullopt
// when it can. Loads it on the first call (thread-safe); later calls are free.
std::optional<std::string> denoising_unavailable();

// Prints "<who>: denoising is unavailable (<why>)..." to stderr the first time it is called in
// the process with the library missing; returns whether the library is available.
bool denoising_available_or_warn_once(const std::string& who);

enum class DenoiseQuality { fast, high };

// One OIDN device (OIDN_DEVICE_TYPE_DEFAULT: its CUDA device where a CUDA GPU and driver are
// present, else the CPU) and a filter kept for the image size of the last call. Use one object
// from one thread at a time.
class Denoiser {
 public:
  // Throws DenoiseError when the library is unavailable or the device cannot be created.
  explicit Denoiser(DenoiseQuality quality = DenoiseQuality::high);
  ~Denoiser();
  Denoiser(const Denoiser&) = delete;
  Denoiser& operator=(const Denoiser&) = delete;

  // The denoised linear colour (RGB; alpha copied from `color`). `albedo` and `normal` (RGB,
  // alpha ignored) guide it when given; a normal image needs an albedo image too. All images
  // must have color's size. Throws DenoiseError with OIDN's message on failure.
  Image denoise(const Image& color, const Image* albedo = nullptr, const Image* normal = nullptr);

  // "CPU", "CUDA", ...: the device OIDN picked.
  const std::string& device_name() const { return device_name_; }

 private:
  struct State;
  std::unique_ptr<State> state_;
  std::string device_name_;
};

}  // namespace glint
