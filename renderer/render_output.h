// Writing a finished render with the optional denoised colour and auxiliary images (docs/
// DESIGN.md, Denoising): the one writer of final images, for `glint render` and the editor's
// export alike. By the file's extension: .png the tonemapped image (tonemapped() below, on the
// CPU), .hdr the linear radiance, .exr float32 layers; alpha is 1, or with
// RenderOutputOptions::alpha the coverage of a transparent background. Denoising is BIASED
// (renderer/denoiser.h): the caller labels it so.
#pragma once

#include <filesystem>
#include <string>

#include "renderer/aov_pass.h"
#include "renderer/denoiser.h"
#include "renderer/image.h"
#include "renderer/image_metadata.h"
#include "renderer/scene.h"

namespace glint {

class GpuRenderer;

struct RenderOutputOptions {
  // The albedo and normal images (the renderer must have had set_aovs_enabled(true) for the
  // whole render) as the EXR layers albedo.R/G/B and N.X/Y/Z. .exr only.
  bool aovs = false;
  // The output is the denoised colour; an EXR keeps the noisy one as the layer noisy.R/G/B.
  // Needs the AOVs too. The noisy image is always written first: without the library, or when
  // the denoiser fails, it is what the file holds and `note` says so.
  bool denoise = false;
  DenoiseQuality quality = DenoiseQuality::high;
  // Written into the file: PNG text chunks, Radiance header lines, OpenEXR string attributes
  // (renderer/image_metadata.h; a render's provenance: renderer/render_metadata.h).
  ImageMetadata metadata;
  // A transparent background (.png and .exr; the renderer must have traced with
  // RenderOptions::transparent_background): alpha is each pixel's coverage
  // (GpuRenderer::read_coverage), 0 where the camera sees the environment, fractional on
  // antialiased edges. The EXR holds premultiplied RGBA (OpenEXR's convention, what the render
  // is); the PNG straight alpha (its convention): the tonemap of colour / alpha.
  bool alpha = false;
};

struct RenderOutputReport {
  bool denoised = false;
  double denoise_seconds = 0;  // the filter's wall time, buffers included
  std::string device;          // the OIDN device that ran it
  bool denoise_failed = false;  // the library was there but the denoiser failed (an error for the caller)
  std::string note;            // why it was not denoised, when asked to and it was not
};

// The render's linear colour with alpha 1 (the accumulation's alpha holds the discarded count).
Image render_colour(const GpuRenderer& renderer);

// The display image of a linear one, by the formula of the GPU's tonemap pass (shaders/lib/
// tonemap.glsl, here compiled as C++), alpha 1: what a PNG holds. The GPU's own display image
// may differ from it by one 8-bit level where the driver rounds differently (docs/DESIGN.md
// §11, Outputs).
Image tonemapped(const Image& linear, const DisplaySettings& display);

// What a finished render writes, read back from the GPU (on the GL thread).
struct RenderImages {
  Image colour;    // linear, alpha 1
  AovImages aovs;  // empty when the renderer had no AOVs enabled
  Image coverage;  // with `coverage` below (rgba alike), else empty
};
RenderImages read_render_images(const GpuRenderer& renderer, bool coverage = false);

// `colour` with its alpha set to `coverage`'s (same size): premultiplied RGBA.
Image with_alpha(const Image& colour, const Image& coverage);
// The display image of a premultiplied one with straight alpha: tonemapped(colour / alpha),
// 0 where alpha is 0, and alpha kept (a transparent PNG).
Image tonemapped_straight_alpha(const Image& premultiplied, const DisplaySettings& display);

// Writes `file` (atomically) from images already read back: needs no GL, so it may run on a
// worker thread. Throws ImageError naming the file. A denoiser that fails leaves the noisy
// image written and says so in the report (denoise_failed, note). `denoiser`: one to reuse, or
// nullptr for a new one.
RenderOutputReport save_render_images(const RenderImages& images, const DisplaySettings& display,
                                      const std::filesystem::path& file,
                                      const RenderOutputOptions& options, Denoiser* denoiser = nullptr);

// The same straight from the renderer (on the GL thread), reading back the AOVs only when the
// options need them.
RenderOutputReport save_render_output(GpuRenderer& renderer, const DisplaySettings& display,
                                      const std::filesystem::path& file,
                                      const RenderOutputOptions& options,
                                      Denoiser* denoiser = nullptr);

}  // namespace glint
