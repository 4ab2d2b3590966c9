#include "renderer/scene_images.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>

#include "renderer/float_limits.h"
#include "renderer/image.h"
#include "renderer/json_fields.h"
#include "renderer/scene_validation.h"
#include "renderer/texture_cache.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

// The shader's environment radiance is a texel times environment.intensity, in float: each is
// within its own limit, but the product must be too (float_limits.h, kMaxRadiance).
void check_environment_radiance(const Scene& scene, const TextureImage& texture,
                                std::vector<ProjectError>& problems) {
  float brightest = texture.eight_bit() ? 1.0f : 0.0f;
  const std::vector<float>& pixels = texture.linear.pixels;
  for (size_t i = 0; i < pixels.size(); ++i)
    if (i % 4 != 3) brightest = std::max(brightest, pixels[i]);
  const float intensity = scene.environment.intensity;
  const double product = double(brightest) * intensity;  // in double: finite for the message
  char product_text[32];
  std::snprintf(product_text, sizeof product_text, "%.3g", product);
  if (std::isfinite(intensity) && !(product <= kMaxRadiance))
    problems.emplace_back("", "environment.intensity",
                          "times the brightest texel of the environment (" +
                              json_fields::float_text(brightest) + ") gives a radiance of " +
                              product_text + ", above the limit of " +
                              json_fields::float_text(kMaxRadiance) +
                              " (the renderer's 32-bit floats would overflow)");
}

}  // namespace

std::vector<ProjectError> check_scene_images(const Scene& scene) {
  struct Named {
    std::string json_path;
    fs::path file;
    bool environment = false;
  };
  std::vector<Named> images;
  // A path with a NUL byte is validate_scene's problem: no file name can hold it.
  auto name = [&](std::string json_path, const std::string& path, bool environment) {
    if (!path.empty() && path.find('\0') == std::string::npos)
      images.push_back({std::move(json_path), resolve_asset_path(scene, path), environment});
  };
  for (size_t i = 0; i < scene.textures.size(); ++i)
    name(json_fields::child_path(json_fields::index_path("textures", i), "path"),
         scene.textures[i].path, false);
  name("environment.texture", scene.environment.texture, true);

  std::vector<ProjectError> problems;
  auto add = [&](const Named& image, std::string problem) {
    problems.emplace_back("", image.json_path, std::move(problem));
  };
  // Headers first: the whole estimate is known before a single texel is decoded.
  std::vector<std::pair<dev_t, ino_t>> counted;  // texture files already in the estimate
  double total = 0;
  for (const Named& image : images) {
    ImageInfo info;
    try {
      info = probe_image(image.file);
    } catch (const std::exception& e) {  // ImageError, or a filesystem error
      add(image, std::string("cannot read image: ") + e.what());
      continue;
    }
    struct stat st {};
    if (!image.environment && ::stat(image.file.c_str(), &st) == 0) {
      const std::pair<dev_t, ino_t> id{st.st_dev, st.st_ino};
      if (std::find(counted.begin(), counted.end(), id) != counted.end()) continue;  // decoded once
      counted.push_back(id);
    }
    const int per_texel = image.environment ? 20 : info.high_dynamic_range ? 16 : 4;
    const double bytes = double(info.width) * info.height * per_texel;
    total += bytes;
    if (total > double(kMaxImageBytes) && problems.empty())
      add(image, image.file.string() + ": a " + std::to_string(info.width) + "x" +
                     std::to_string(info.height) + (info.high_dynamic_range ? " float" : " 8-bit") +
                     (image.environment ? " environment" : " texture") + " takes " +
                     bytes_text(bytes) + " (" + std::to_string(per_texel) +
                     " bytes per texel), which brings the textures and environment to " +
                     bytes_text(total) + "; the limit is " + bytes_text(double(kMaxImageBytes)));
  }
  if (!problems.empty()) return problems;
  // Decoded once each (the renderer uploads these same texels): truncated data, a missing
  // channel or a bad texel is found now, not when the scene is first rendered.
  for (const Named& image : images) {
    try {
      const std::shared_ptr<const TextureImage> texture = load_texture_cached(image.file);
      if (image.environment) check_environment_radiance(scene, *texture, problems);
    } catch (const std::exception& e) {
      add(image, std::string("cannot read image: ") + e.what());
    }
  }
  return problems;
}

}  // namespace glint
