#include "renderer/scene_textures.h"

#include <algorithm>
#include <limits>
#include <string>

#include "renderer/environment_distribution.h"
#include "renderer/gl_objects.h"
#include "renderer/mnee_casters.h"
#include "renderer/scene_tables.h"
#include "renderer/scene_validation.h"
#include "renderer/shader_lib.h"
#include "renderer/texture_cache.h"

namespace glint {
namespace {

std::string json_path(const TextureLayer& layer) { return "textures[" + std::to_string(layer.texture) + "].path"; }

// Texels that a texture of kTexelRowWidth x GL_MAX_TEXTURE_SIZE holds, or `option` when
// positive (tests); at most INT_MAX (texel indices are ints in the shader).
int64_t texel_limit(int64_t option) {
  int64_t limit = option;
  if (limit <= 0) {
    GLint max_side = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
    limit = int64_t(kTexelRowWidth) * max_side;
  }
  return std::min<int64_t>(limit, std::numeric_limits<int>::max());
}

// Copies `count` texels of `texel_bytes` each to texels [first, first + count) of `texture`, a
// 2-D texture read row after row (rows of kTexelRowWidth): a partial first row, the whole rows, a
// partial last row.
void upload_texel_run(GLuint texture, GLenum format, GLenum type, int64_t texel_bytes,
                      int64_t first, int64_t count, const unsigned char* data) {
  auto put = [&](int64_t x, int64_t y, int64_t width, int64_t height) {
    glTextureSubImage2D(texture, 0, static_cast<GLint>(x), static_cast<GLint>(y),
                        static_cast<GLsizei>(width), static_cast<GLsizei>(height), format, type, data);
    data += width * height * texel_bytes;
    first += width * height;
    count -= width * height;
  };
  constexpr int64_t w = kTexelRowWidth;
  if (count > 0 && first % w != 0) put(first % w, first / w, std::min(count, w - first % w), 1);
  if (count >= w) put(0, first / w, w, count / w);
  if (count > 0) put(0, first / w, count, 1);
}

// Makes textures[k] and fills it with the plan's runs of kind k, for both kinds; returns "" or
// what the driver refused.
std::string upload_texel_sequences(const TexelPlan& plan, GLuint textures[2]) {
  const GLenum formats[2] = {GL_RGBA8, GL_RGBA32F};
  const GLenum types[2] = {GL_UNSIGNED_BYTE, GL_FLOAT};
  const int64_t texel_bytes[2] = {4, 16};
  for (int k = 0; k < 2; ++k) {
    // Never empty: a texture needs storage to be complete.
    const int64_t rows = std::max<int64_t>(1, (plan.texels[k] + kTexelRowWidth - 1) / kTexelRowWidth);
    glTextureStorage2D(textures[k], 1, formats[k], kTexelRowWidth, static_cast<GLsizei>(rows));
    glTextureParameteri(textures[k], GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(textures[k], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    if (const std::string failure = gl_error_text(); !failure.empty())
      return "cannot allocate " + bytes_text(double(rows) * kTexelRowWidth * texel_bytes[k]) + " for the " +
             (k ? "float" : "8-bit") + " textures (" + failure + ")";
    for (const TexelPlan::Run& run : plan.runs[k]) {
      const auto* data = k ? reinterpret_cast<const unsigned char*>(run.image->linear.pixels.data())
                           : reinterpret_cast<const unsigned char*>(run.image->rgba8.data());
      upload_texel_run(textures[k], GL_RGBA, types[k], texel_bytes[k], run.first,
                       int64_t(run.image->width()) * run.image->height(), data);
    }
    if (const std::string failure = gl_error_text(); !failure.empty())
      return "cannot upload the textures (" + failure + ")";
  }
  return "";
}

}  // namespace

TexelPlan plan_texels(const std::vector<TextureLayer>& layers,
                      const std::vector<std::shared_ptr<const TextureImage>>& images,
                      const std::vector<std::filesystem::path>& files, int64_t limit) {
  TexelPlan plan;
  for (size_t i = 0; i < layers.size(); ++i) {
    const TextureImage& image = *images[i];
    const int kind = image.eight_bit() ? 0 : 1;
    std::vector<TexelPlan::Run>& runs = plan.runs[kind];
    auto run = std::find_if(runs.begin(), runs.end(), [&](const TexelPlan::Run& r) { return r.image == &image; });
    if (run == runs.end()) {
      runs.push_back({&image, plan.texels[kind]});
      run = runs.end() - 1;
      plan.texels[kind] += int64_t(image.width()) * image.height();
      if (plan.texels[kind] > limit)
        throw ImageError(json_path(layers[i]) + ": " + files[i].string() + ": the textures need " +
                         std::to_string(plan.texels[kind]) + (kind ? " float" : " 8-bit") +
                         " texels, more than this OpenGL driver holds (" + std::to_string(limit) +
                         " texels: " + std::to_string(kTexelRowWidth) + " per row, GL_MAX_TEXTURE_SIZE rows)");
    }
    const int format = kind ? gpu::TEXELS_FLOAT
                            : layers[i].encoding == ColorEncoding::srgb ? gpu::TEXELS_8BIT_SRGB
                                                                        : gpu::TEXELS_8BIT_LINEAR;
    plan.records.emplace_back(image.width(), image.height(), static_cast<int>(run->first), format);
  }
  return plan;
}

SceneTextures::SceneTextures(int64_t max_texels) : max_texels_(max_texels) {}

SceneTextures::~SceneTextures() {
  glDeleteTextures(2, texel_textures_);
  if (environment_texture_) glDeleteTextures(1, &environment_texture_);
}

void SceneTextures::upload_textures(const Scene& scene, const std::vector<TextureLayer>& layers,
                                    SceneTables& tables) {
  // Decoded once, by load_project when it checked the files (renderer/texture_cache.h).
  std::vector<std::shared_ptr<const TextureImage>> images;
  std::vector<std::filesystem::path> files;
  for (const TextureLayer& layer : layers) {
    try {
      files.push_back(resolve_asset_path(scene, scene.textures[layer.texture].path));
      images.push_back(load_texture_cached(files.back()));
    } catch (const ImageError& e) {
      throw ImageError(json_path(layer) + ": " + e.what());
    }
  }
  // Offsets are ints in the shader, and the driver caps a texture's rows.
  const TexelPlan plan = plan_texels(layers, images, files, texel_limit(max_texels_));
  // New textures first: should the driver refuse one, the previous ones stay in place.
  clear_gl_errors();
  GLuint textures[2] = {0, 0};
  glCreateTextures(GL_TEXTURE_2D, 2, textures);
  if (const std::string failure = upload_texel_sequences(plan, textures); !failure.empty()) {
    glDeleteTextures(2, textures);
    throw ImageError("textures: " + failure);  // all of them together
  }
  glDeleteTextures(2, texel_textures_);
  std::copy(textures, textures + 2, texel_textures_);
  tables.upload(SceneTable::layers, plan.records);
  layers_ = layers;
}

glm::ivec2 SceneTextures::upload_environment(const Scene& scene, SceneTables& tables) {
  const Environment& env = scene.environment;
  std::shared_ptr<const TextureImage> texture;
  Image converted;
  const Image* image = &converted;
  // Problems read "environment.texture: FILE: ...", as the loader's do (ImageError's what()
  // names the file already).
  const std::string json_path = "environment.texture: ";
  std::string where = json_path;
  if (!env.texture.empty()) {
    const std::filesystem::path file = resolve_asset_path(scene, env.texture);
    where += file.string() + ": ";
    try {
      texture = load_texture_cached(file);
    } catch (const ImageError& e) {
      throw ImageError(json_path + e.what());
    }
    if (texture->eight_bit())
      converted = to_linear_image(*texture, ColorEncoding::linear);
    else
      image = &texture->linear;
  } else {
    converted.width = converted.height = 1;
    converted.pixels = {1, 1, 1, 1};
  }
  GLint max_side = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
  if (image->width > max_side || image->height > max_side)
    throw ImageError(where + std::to_string(image->width) + "x" + std::to_string(image->height) +
                     " is more than this OpenGL driver holds (" + std::to_string(max_side) +
                     " texels per side, GL_MAX_TEXTURE_SIZE)");
  const EnvironmentDistribution unpacked = build_environment_distribution(*image);
  const double peak_share = env.texture.empty() ? 0.0 : glint::environment_peak_share(unpacked, kPeakSolidAngleShare);
  PackedEnvironmentDistribution distribution = pack_environment_distribution(unpacked);
  try {
    tables.check_size("its sampling tables' floats", distribution.data);
  } catch (const std::runtime_error& e) {
    throw ImageError(where + e.what());
  }
  clear_gl_errors();
  GLuint texture_id = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture_id);
  glTextureStorage2D(texture_id, 1, GL_RGBA32F, image->width, image->height);
  std::string failure = gl_error_text();
  if (failure.empty()) {
    glTextureSubImage2D(texture_id, 0, 0, 0, image->width, image->height, GL_RGBA, GL_FLOAT,
                        image->pixels.data());
    failure = gl_error_text();
  }
  if (!failure.empty()) {
    glDeleteTextures(1, &texture_id);
    throw ImageError(where + "cannot allocate " + bytes_text(double(image->width) * image->height * 16) +
                     " for it (" + failure + ")");
  }
  if (environment_texture_) glDeleteTextures(1, &environment_texture_);
  environment_texture_ = texture_id;
  environment_peak_share_ = peak_share;
  glTextureParameteri(environment_texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(environment_texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(environment_texture_, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(environment_texture_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  tables.upload(SceneTable::environment, distribution.data);
  if (const std::string error = gl_error_text(); !error.empty())
    throw ImageError(where + "cannot allocate " + bytes_text(double(distribution.data.size()) * sizeof(float)) +
                     " for its sampling tables (" + error + ")");
  return {distribution.width, distribution.height};
}

}  // namespace glint
