#include "renderer/render_output.h"

#include <chrono>
#include <memory>
#include <new>
#include <optional>
#include <vector>

#include "renderer/gpu_renderer.h"
#include "renderer/shader_lib.h"
#include "renderer/stopwatch.h"

namespace glint {

Image render_colour(const GpuRenderer& renderer) {
  Image image = renderer.read_accumulation();
  for (size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 1.0f;
  return image;
}

Image tonemapped(const Image& linear, const DisplaySettings& display) {
  Image out = linear;
  const int mode = display.tonemap == Tonemap::filmic ? gpu::TONEMAP_FILMIC : gpu::TONEMAP_LINEAR;
  for (size_t i = 0; i < out.pixels.size(); i += 4) {
    const glm::vec3 c = gpu::tonemap(glm::vec3(out.pixels[i], out.pixels[i + 1], out.pixels[i + 2]),
                                     display.exposure, mode);
    out.pixels[i] = c.x, out.pixels[i + 1] = c.y, out.pixels[i + 2] = c.z, out.pixels[i + 3] = 1.0f;
  }
  return out;
}

RenderImages read_render_images(const GpuRenderer& renderer, bool coverage) {
  return {render_colour(renderer), renderer.read_aovs(), coverage ? renderer.read_coverage() : Image{}};
}

Image with_alpha(const Image& colour, const Image& coverage) {
  Image out = colour;
  for (size_t i = 3; i < out.pixels.size() && i < coverage.pixels.size(); i += 4)
    out.pixels[i] = coverage.pixels[i];
  return out;
}

Image tonemapped_straight_alpha(const Image& premultiplied, const DisplaySettings& display) {
  Image straight = premultiplied;
  for (size_t i = 0; i < straight.pixels.size(); i += 4) {
    const float a = premultiplied.pixels[i + 3];
    for (int c = 0; c < 3; ++c) straight.pixels[i + c] = a > 0 ? straight.pixels[i + c] / a : 0.0f;
  }
  Image out = tonemapped(straight, display);
  for (size_t i = 3; i < out.pixels.size(); i += 4) out.pixels[i] = premultiplied.pixels[i];
  return out;
}

namespace {

// Writes `colour` as `file` by its extension: PNG tonemapped, HDR linear, EXR with the layers
// asked for (`noisy` beside a denoised colour, the AOVs).
// With `coverage`, `colour` is premultiplied by it and it becomes the alpha.
void write_output(const std::filesystem::path& file, const Image& colour_in, const Image* noisy,
                  const AovImages* aovs, const DisplaySettings& display, const ImageMetadata& metadata,
                  const Image* coverage) {
  const Image colour = coverage ? with_alpha(colour_in, *coverage) : colour_in;
  const std::string ext = file.extension().string();
  if (ext == ".png") {
    save_image(file, coverage ? tonemapped_straight_alpha(colour, display) : tonemapped(colour, display),
               metadata);
  } else if (ext != ".exr") {
    save_image(file, colour, metadata);
  } else {
    std::vector<ExrLayer> layers{{"", &colour, "RGBA"}};
    if (noisy) layers.push_back({"noisy", noisy, "RGB"});
    if (aovs) {
      layers.push_back({"albedo", &aovs->albedo, "RGB"});
      layers.push_back({"N", &aovs->normal, "XYZ"});
    }
    save_exr_layers(file, layers, metadata);
  }
}

}  // namespace

RenderOutputReport save_render_images(const RenderImages& images, const DisplaySettings& display,
                                      const std::filesystem::path& file,
                                      const RenderOutputOptions& options, Denoiser* denoiser) {
  RenderOutputReport report;
  const Image& noisy = images.colour;
  const AovImages& aovs = images.aovs;
  const AovImages* layers = options.aovs && !aovs.albedo.pixels.empty() ? &aovs : nullptr;
  // The noisy render first: a denoiser that fails (a device plugin missing or broken, memory
  // exhausted at a large size) must not cost the finished render.
  const Image* coverage = options.alpha && !images.coverage.pixels.empty() ? &images.coverage : nullptr;
  write_output(file, noisy, nullptr, layers, display, options.metadata, coverage);
  if (!options.denoise) return report;
  if (const auto why = denoising_unavailable()) {
    report.note = "denoising is unavailable (" + *why + "): the noisy image was written";
    return report;
  }
  std::optional<Image> denoised;
  try {
    std::unique_ptr<Denoiser> own;
    if (!denoiser) denoiser = (own = std::make_unique<Denoiser>(options.quality)).get();
    const auto start = std::chrono::steady_clock::now();
    const bool guided = !aovs.albedo.pixels.empty();
    denoised = guided ? denoiser->denoise(noisy, &aovs.albedo, &aovs.normal) : denoiser->denoise(noisy);
    report.denoise_seconds = seconds_since(start);
    report.device = denoiser->device_name();
  } catch (const std::bad_alloc&) {
    report.denoise_failed = true;
    report.note = "denoising failed (out of memory at " + std::to_string(noisy.width) + "x" +
                  std::to_string(noisy.height) + "): " + file.string() + " holds the noisy image";
    return report;
  } catch (const DenoiseError& e) {
    report.denoise_failed = true;
    report.note = std::string("denoising failed (") + e.what() + "): " + file.string() + " holds the noisy image";
    return report;
  }
  write_output(file, *denoised, &noisy, layers, display, options.metadata, coverage);
  report.denoised = true;
  return report;
}

RenderOutputReport save_render_output(GpuRenderer& renderer, const DisplaySettings& display,
                                      const std::filesystem::path& file,
                                      const RenderOutputOptions& options, Denoiser* denoiser) {
  RenderImages images{render_colour(renderer), {}, {}};
  if (options.aovs || options.denoise) images.aovs = renderer.read_aovs();
  if (options.alpha) images.coverage = renderer.read_coverage();
  return save_render_images(images, display, file, options, denoiser);
}

}  // namespace glint
