#include "renderer/gpu_renderer.h"

#include <algorithm>
#include <bit>
#include <initializer_list>
#include <chrono>
#include <cstdio>
#include <limits>
#include <memory>
#include <thread>
#include <stdexcept>
#include <vector>

#include "renderer/camera_frame.h"
#include "renderer/environment_distribution.h"
#include "renderer/error_estimate.h"
#include "renderer/gl_context.h"
#include "renderer/gl_program.h"
#include "renderer/llvmpipe_threads.h"
#include "renderer/loop_budget.h"
#include "renderer/loop_shapes.h"
#include "renderer/path_restart.h"
#include "renderer/gpu_scene.h"
#include "renderer/program_worker.h"
#include "renderer/scene_validation.h"
#include "renderer/shader_lib.h"
#include "renderer/texture_cache.h"

namespace glint {
namespace {

void clear_gl_errors() {
  while (glGetError() != GL_NO_ERROR) {
  }
}

// The first OpenGL error since the last call (all are cleared), or "" if none.
std::string gl_error_text() {
  const GLenum error = glGetError();
  if (error == GL_NO_ERROR) return "";
  clear_gl_errors();
  if (error == GL_OUT_OF_MEMORY) return "the OpenGL driver is out of memory";
  char text[64];
  std::snprintf(text, sizeof text, "OpenGL error 0x%04x", error);
  return text;
}

GLuint make_texture_2d(GLenum internal_format, int width, int height) {
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, internal_format, width, height);
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

// A framebuffer drawing into `textures` at locations 0, 1, ...
GLuint make_framebuffer(std::initializer_list<GLuint> textures) {
  GLuint fbo = 0;
  glCreateFramebuffers(1, &fbo);
  std::vector<GLenum> attachments;
  for (GLuint t : textures) {
    const GLenum a = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(attachments.size());
    glNamedFramebufferTexture(fbo, a, t, 0);
    attachments.push_back(a);
  }
  glNamedFramebufferDrawBuffers(fbo, static_cast<GLsizei>(attachments.size()), attachments.data());
  if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("incomplete framebuffer for the render target");
  return fbo;
}

// The trace pass's four targets of one ping-pong side.
GLuint make_trace_framebuffer(const TraceTargets& t) {
  return make_framebuffer({t.accumulation, t.compensation, t.variance, t.variance_compensation});
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
  constexpr int64_t w = GpuRenderer::kTexelRowWidth;
  if (count > 0 && first % w != 0) put(first % w, first / w, std::min(count, w - first % w), 1);
  if (count >= w) put(0, first / w, w, count / w);
  if (count > 0) put(0, first / w, count, 1);
}

// Texels that a texture of kTexelRowWidth x GL_MAX_TEXTURE_SIZE holds, or `option` when
// positive (tests); at most INT_MAX (texel indices are ints in the shader).
int64_t texel_limit(int64_t option) {
  int64_t limit = option;
  if (limit <= 0) {
    GLint max_side = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
    limit = int64_t(GpuRenderer::kTexelRowWidth) * max_side;
  }
  return std::min<int64_t>(limit, std::numeric_limits<int>::max());
}

// Texels that a buffer texture holds (GL_MAX_TEXTURE_BUFFER_SIZE), or `option` when positive
// (tests); at most INT_MAX.
int64_t table_limit(int64_t option) {
  int64_t limit = option;
  if (limit <= 0) {
    GLint max_texels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    limit = max_texels;
  }
  return std::min<int64_t>(limit, std::numeric_limits<int>::max());
}

}  // namespace

GpuRenderer::GpuRenderer(GpuRendererOptions options) : renderer_options_(options) {
  trace_program_ = start_trace_program(options.backend, options.work_group, "");
  trace_program_->finish();
  tonemap_program_ = std::make_unique<GlProgram>("fullscreen.vert", "tonemap.frag");
  estimator_ = std::make_unique<ErrorEstimator>();
  glCreateVertexArrays(1, &vao_);
  glCreateTextures(GL_TEXTURE_BUFFER, kTables, table_textures_);
  glCreateBuffers(kTables, table_buffers_);
  glCreateBuffers(1, &loop_shapes_buffer_);
  const LoopShapesBlock empty;
  glNamedBufferData(loop_shapes_buffer_, sizeof empty, &empty, GL_DYNAMIC_DRAW);
  llvmpipe_ = on_llvmpipe();
  // One CPU per llvmpipe thread, so that short passes use every CPU (llvmpipe_threads.h).
  if (llvmpipe_) pin_llvmpipe_threads();
  // Every table is bound for every pass: never without storage, even before a scene or a BVH
  // exists.
  upload_table(0, std::vector<GpuSphere>{});
  upload_table(1, std::vector<GpuQuad>{});
  upload_table(2, std::vector<GpuMaterial>{});
  upload_table(3, std::vector<glm::ivec4>{});
  upload_table(4, std::vector<GpuLight>{});
  upload_table(5, std::vector<float>{});
  upload_table(6, std::vector<GpuBvhNode>{});
  upload_table(7, std::vector<int32_t>{});
}

GpuRenderer::~GpuRenderer() {
  estimator_.reset();
  resize(0, 0);
  glDeleteTextures(kTables, table_textures_);
  glDeleteBuffers(kTables, table_buffers_);
  glDeleteBuffers(1, &loop_shapes_buffer_);
  glDeleteVertexArrays(1, &vao_);
  if (!trace_timers_.empty()) glDeleteQueries(static_cast<GLsizei>(trace_timers_.size()), trace_timers_.data());
  glDeleteTextures(2, texel_textures_);
  if (environment_texture_) glDeleteTextures(1, &environment_texture_);
}

void GpuRenderer::resize(int width, int height) {
  if (accumulation_[0]) {
    glDeleteFramebuffers(2, accumulation_fbo_);  // names of 0 are ignored
    accumulation_fbo_[0] = accumulation_fbo_[1] = 0;
    glDeleteTextures(2, accumulation_);
    glDeleteTextures(2, compensation_);
    glDeleteTextures(2, variance_);
    glDeleteTextures(2, variance_compensation_);
    glDeleteFramebuffers(1, &display_fbo_);
    glDeleteTextures(1, &display_texture_);
    for (int i = 0; i < 2; ++i)
      accumulation_[i] = compensation_[i] = variance_[i] = variance_compensation_[i] = 0;
    display_texture_ = 0;
  }
  width_ = width;
  height_ = height;
  if (width <= 0 || height <= 0) return;
  const bool compute = renderer_options_.backend == TraceBackend::compute;
  for (int i = 0; i < (compute ? 1 : 2); ++i) {
    accumulation_[i] = make_texture_2d(GL_RGBA32F, width, height);
    compensation_[i] = make_texture_2d(GL_RGBA32F, width, height);
    variance_[i] = make_texture_2d(GL_RGBA32F, width, height);
    variance_compensation_[i] = make_texture_2d(GL_RGBA32F, width, height);
    if (!compute) accumulation_fbo_[i] = make_trace_framebuffer(targets(i));
  }
  display_texture_ = make_texture_2d(GL_RGBA8, width, height);
  // Shown scaled when the editor previews at reduced resolution: smooth, not blocky.
  glTextureParameteri(display_texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  display_fbo_ = make_framebuffer({display_texture_});
  if (aov_pass_) aov_pass_->resize(width, height);
}

SyncResult GpuRenderer::sync(const Scene& scene, int width, int height) {
  // The film limits of a project hold for every caller (and before anything changes): a
  // larger image would fail to allocate, or crash the driver, only after gigabytes.
  if (width > 0 && height > 0)
    if (const auto problem = check_film_size(width, height))
      throw std::runtime_error("cannot render a " + std::to_string(width) + "x" +
                               std::to_string(height) + " image: " + problem->what());
  SceneDigests d = digest_scene(scene);
  SyncResult result;
  const glm::dvec3 origin = render_origin(scene.camera.position);
  // The textures too: the materials' layer indices follow the texture list, and a texture
  // whose file changed must be uploaded with the layers that read it.
  const bool geometry_changed = first_sync_ || d.geometry != digests_.geometry ||
                                d.materials != digests_.materials ||
                                d.textures != digests_.textures || origin != origin_;
  PackedScene packed;
  if (geometry_changed) packed = pack_scene(scene, origin);
  // Images first: if one fails to load, nothing has changed yet. Textures are reloaded only
  // when their files or the set of layers in use change, not on every material edit.
  if (first_sync_ || d.textures != digests_.textures || (geometry_changed && packed.layers != layers_))
    upload_textures(scene, packed.layers);
  if (first_sync_ || d.environment != digests_.environment) upload_environment(scene);
  if (geometry_changed) {
    upload_geometry(packed);
    origin_ = origin;
  }
  use_bvh_ = use_bvh(options_.accel, static_cast<long>(scene.spheres.size() + scene.quads.size()),
                     scene.render.max_bounces);
  if (use_bvh_) {
    // The boxes are padded for ray origins up to the camera's distance from the render origin
    // (bvh.cpp): a camera beyond that needs wider boxes.
    const glm::vec3 camera(glm::dvec3(scene.camera.position) - origin_);
    const float camera_extent = std::max({std::abs(camera.x), std::abs(camera.y), std::abs(camera.z)});
    if (geometry_changed || !bvh_valid_ || !(camera_extent <= bvh_extent_)) {
      if (!geometry_changed) packed = pack_scene(scene, origin_);
      update_bvh(packed, camera);
    }
  }
  // Features: the texture alpha probe only when what it depends on changed; the lens is cheap.
  if (geometry_changed || first_sync_ || d.textures != digests_.textures ||
      d.environment != digests_.environment)
    features_ = scene_features(scene);
  features_.thin_lens = scene.camera.aperture_radius > 0;
  features_.loop_traversal = !use_bvh_;
  features_.bvh_traversal = use_bvh_;
  features_.sobol_sampler = options_.sampler == SamplerKind::sobol;
  features_.pcg_sampler = !features_.sobol_sampler;
  features_ = with_loop_counts(features_, static_cast<long>(scene.spheres.size()),
                               static_cast<long>(scene.quads.size()));
  if (width != width_ || height != height_) {
    resize(width, height);
    result.accumulation_reset = true;
  }
  if (first_sync_ || d.radiance() != digests_.radiance() || options_ != synced_options_)
    result.accumulation_reset = true;
  if (result.accumulation_reset) set_frame_uniforms(scene);  // the aspect ratio may have changed
  if (first_sync_ || d.display != digests_.display) {
    tonemap_program_->set("u_exposure", scene.display.exposure);
    tonemap_program_->set("u_tonemap", scene.display.tonemap == Tonemap::filmic ? 0 : 1);
    result.display_changed = true;
    display_stale_ = true;
  }
  if (result.accumulation_reset) {
    pass_ = {};  // a pass under way is abandoned
    samples_ = 0;
    passes_ = 0;
    threshold_samples_ = 0;
    adaptive_threshold_ = 0;
    estimate_ = {};
    estimate_samples_ = -1;
    display_stale_ = true;
    if (!trace_timers_.empty()) glDeleteQueries(static_cast<GLsizei>(trace_timers_.size()), trace_timers_.data());
    trace_timers_.clear();
    trace_gpu_seconds_ = 0;
    const float zero[4] = {0, 0, 0, 0};
    for (int i = 0; i < 2; ++i)
      for (GLuint t : {accumulation_[i], compensation_[i], variance_[i], variance_compensation_[i]})
        if (t) glClearTexImage(t, 0, GL_RGBA, GL_FLOAT, zero);
    if (aov_pass_) aov_pass_->clear();
  }
  digests_ = d;
  synced_options_ = options_;
  first_sync_ = false;
  return result;
}

// A refit where only shapes moved (same counts) and the tree has not degraded much (SAH cost
// within 1.5 times that of its build, Wald 2007's measure of tree quality); a build otherwise.
void GpuRenderer::update_bvh(const PackedScene& packed, const glm::vec3& camera) {
  const auto start = std::chrono::steady_clock::now();
  const float extent = ray_extent(packed.spheres, packed.quads, camera);
  bool refit = !bvh_.primitives.empty() && refit_bvh(bvh_, packed.spheres, packed.quads, extent);
  if (refit && sah_cost(bvh_) > 1.5 * bvh_built_cost_) refit = false;
  if (!refit) {
    bvh_ = build_bvh(packed.spheres, packed.quads, extent);
    bvh_built_cost_ = sah_cost(bvh_);
  }
  bvh_extent_ = extent;
  bvh_valid_ = true;
  check_table_size("the BVH's nodes", bvh_.nodes);
  check_table_size("the BVH's primitive list", bvh_.primitives);
  upload_table(6, bvh_.nodes);
  upload_table(7, bvh_.primitives);
  bvh_stats_.nodes = bvh_.nodes.size();
  bvh_stats_.depth = bvh_.depth;
  bvh_stats_.refit = refit;
  bvh_stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The texels a table of `data` needs (one per 16 bytes, or one per int or float).
template <typename T>
int64_t table_texels(const std::vector<T>& data) {
  static_assert(sizeof(T) % 16 == 0 || sizeof(T) == 4, "an RGBA32I or R32I texel layout");
  return int64_t(data.size()) * (sizeof(T) % 16 == 0 ? int64_t(sizeof(T) / 16) : 1);
}

template <typename T>
void GpuRenderer::check_table_size(const std::string& what, const std::vector<T>& data) const {
  const int64_t limit = table_limit(renderer_options_.max_table_texels);
  if (table_texels(data) > limit)
    throw std::runtime_error(what + " (" + std::to_string(data.size()) + ") need " +
                             std::to_string(table_texels(data)) +
                             " texels, more than this OpenGL driver holds (" +
                             std::to_string(limit) +
                             " texels in a table: GL_MAX_TEXTURE_BUFFER_SIZE)");
}

// Uploads `data` into table k, the integer buffer texture the trace shader reads it from
// (shaders/trace_common.glsl). The buffer is a power of two of bytes, at least 64 KiB, zeros past
// the data: llvmpipe keys its compiled shaders by whether each bound texture's size is a power
// of two, and by bits 8 to 15 of a buffer texture's byte size (which alias a 2-D texture's last
// mipmap level in gallium's sampler view), so that with any other size a draw could compile the
// program again, on the calling thread, after the worker's warm-up draw (program_worker.h) had
// compiled it for another size. The zeros also stand for the empty table's one element (a lane
// masked off may still read it). The texture and the buffer keep their names (a warm-up job
// holds them).
template <typename T>
void GpuRenderer::upload_table(int k, const std::vector<T>& data) {
  constexpr bool rgba = sizeof(T) % 16 == 0;
  const int64_t bytes = int64_t(data.size()) * int64_t(sizeof(T));
  const int64_t size = std::max<int64_t>(int64_t(1) << 16, std::bit_ceil(static_cast<uint64_t>(bytes)));
  glNamedBufferData(table_buffers_[k], static_cast<GLsizeiptr>(size), nullptr, GL_STATIC_DRAW);
  glClearNamedBufferData(table_buffers_[k], GL_R32I, GL_RED_INTEGER, GL_INT, nullptr);
  if (bytes > 0) glNamedBufferSubData(table_buffers_[k], 0, static_cast<GLsizeiptr>(bytes), data.data());
  glTextureBuffer(table_textures_[k], rgba ? GL_RGBA32I : GL_R32I, table_buffers_[k]);
}

void GpuRenderer::upload_geometry(const PackedScene& packed) {
  // All checked before any is replaced: a refused scene leaves the previous one in place.
  check_table_size("spheres", packed.spheres);
  check_table_size("quads", packed.quads);
  check_table_size("materials", packed.materials);
  check_table_size("lights", packed.lights);
  upload_table(0, packed.spheres);
  upload_table(1, packed.quads);
  upload_table(2, packed.materials);
  upload_table(4, packed.lights);
  const LoopShapesBlock block = loop_shapes_block(packed.spheres, packed.quads);
  glNamedBufferSubData(loop_shapes_buffer_, 0, sizeof block, &block);
  shape_count_ = static_cast<long>(packed.spheres.size() + packed.quads.size());
  light_count_ = static_cast<int>(packed.lights.size());
  uniforms_.sphere_count = static_cast<int>(packed.spheres.size());
  uniforms_.quad_count = static_cast<int>(packed.quads.size());
  bvh_valid_ = false;  // refitted or rebuilt by sync if the BVH is used
}

// Texture storage. The shader filters by hand (lib/mapping.glsl), so each texture is a row-major
// run of texels in one long sequence, stored row after row in a 2-D texture of kTexelRowWidth
// texels a row (2-D, not a buffer texture: that may hold as few as 2^16 texels, 2^27 on
// llvmpipe, and 768 MiB of 8-bit texels are more than 2^27). Memory is the sum of the real
// sizes (a texture array takes the largest width times the largest height for every layer,
// 8 GiB for a 16384x1 and a 1x16384 texture), the count is bounded only by the layer records'
// table (an array by GL_MAX_ARRAY_TEXTURE_LAYERS, 2048 on llvmpipe), and 8-bit textures keep 4
// bytes a texel. There are two sequences because a texture has one format (RGBA8, RGBA32F). An
// atlas would need packing and would still cap a side; arrays per size class would need a
// sampler per class.
void GpuRenderer::upload_textures(const Scene& scene, const std::vector<TextureLayer>& layers) {
  auto json_path = [](const TextureLayer& layer) {
    return "textures[" + std::to_string(layer.texture) + "].path";
  };
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
  const int64_t limit = texel_limit(renderer_options_.max_texture_texels);
  // Each file's texels once, also when several layers read them (colour and roughness).
  struct Run {
    const TextureImage* image;
    int64_t first;
  };
  std::vector<Run> runs[2];  // 8-bit, float
  int64_t texels[2] = {0, 0};
  std::vector<glm::ivec4> records;
  for (size_t i = 0; i < layers.size(); ++i) {
    const TextureImage& image = *images[i];
    const int kind = image.eight_bit() ? 0 : 1;
    auto run = std::find_if(runs[kind].begin(), runs[kind].end(),
                            [&](const Run& r) { return r.image == &image; });
    if (run == runs[kind].end()) {
      runs[kind].push_back({&image, texels[kind]});
      run = runs[kind].end() - 1;
      texels[kind] += int64_t(image.width()) * image.height();
      if (texels[kind] > limit)
        throw ImageError(json_path(layers[i]) + ": " + files[i].string() + ": the textures need " +
                         std::to_string(texels[kind]) + (kind ? " float" : " 8-bit") +
                         " texels, more than this OpenGL driver holds (" + std::to_string(limit) +
                         " texels: " + std::to_string(kTexelRowWidth) + " per row, GL_MAX_TEXTURE_SIZE rows)");
    }
    const int format = kind ? gpu::TEXELS_FLOAT
                            : layers[i].encoding == ColorEncoding::srgb ? gpu::TEXELS_8BIT_SRGB
                                                                        : gpu::TEXELS_8BIT_LINEAR;
    records.emplace_back(image.width(), image.height(), static_cast<int>(run->first), format);
  }
  // New textures first: should the driver refuse one, the previous ones stay in place.
  clear_gl_errors();
  GLuint textures[2] = {0, 0};
  glCreateTextures(GL_TEXTURE_2D, 2, textures);
  const GLenum formats[2] = {GL_RGBA8, GL_RGBA32F};
  const GLenum types[2] = {GL_UNSIGNED_BYTE, GL_FLOAT};
  const int64_t texel_bytes[2] = {4, 16};
  std::string failure;
  for (int k = 0; k < 2 && failure.empty(); ++k) {
    // Never empty: a texture needs storage to be complete.
    const int64_t rows = std::max<int64_t>(1, (texels[k] + kTexelRowWidth - 1) / kTexelRowWidth);
    glTextureStorage2D(textures[k], 1, formats[k], kTexelRowWidth, static_cast<GLsizei>(rows));
    glTextureParameteri(textures[k], GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(textures[k], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    failure = gl_error_text();
    if (!failure.empty()) {
      failure = "cannot allocate " + bytes_text(double(rows) * kTexelRowWidth * texel_bytes[k]) +
                " for the " + (k ? "float" : "8-bit") + " textures (" + failure + ")";
      break;
    }
    for (const Run& run : runs[k]) {
      const auto* data = k ? reinterpret_cast<const unsigned char*>(run.image->linear.pixels.data())
                           : reinterpret_cast<const unsigned char*>(run.image->rgba8.data());
      upload_texel_run(textures[k], GL_RGBA, types[k], texel_bytes[k], run.first,
                       int64_t(run.image->width()) * run.image->height(), data);
    }
    failure = gl_error_text();
    if (!failure.empty()) failure = "cannot upload the textures (" + failure + ")";
  }
  if (!failure.empty()) {
    glDeleteTextures(2, textures);
    throw ImageError("textures: " + failure);  // all of them together
  }
  glDeleteTextures(2, texel_textures_);
  std::copy(textures, textures + 2, texel_textures_);
  upload_table(3, records);
  layers_ = layers;
}

void GpuRenderer::upload_environment(const Scene& scene) {
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
    throw ImageError(where + std::to_string(image->width) +
                     "x" + std::to_string(image->height) + " is more than this OpenGL driver holds (" +
                     std::to_string(max_side) + " texels per side, GL_MAX_TEXTURE_SIZE)");
  PackedEnvironmentDistribution tables =
      pack_environment_distribution(build_environment_distribution(*image));
  try {
    check_table_size("its sampling tables' floats", tables.data);
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
    throw ImageError(where + "cannot allocate " +
                     bytes_text(double(image->width) * image->height * 16) + " for it (" + failure + ")");
  }
  if (environment_texture_) glDeleteTextures(1, &environment_texture_);
  environment_texture_ = texture_id;
  glTextureParameteri(environment_texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(environment_texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(environment_texture_, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(environment_texture_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  upload_table(5, tables.data);
  if (const std::string error = gl_error_text(); !error.empty())
    throw ImageError(where + "cannot allocate " +
                     bytes_text(double(tables.data.size()) * sizeof(float)) +
                     " for its sampling tables (" + error + ")");
  uniforms_.env_distribution_size = glm::ivec2(tables.width, tables.height);
}

void GpuRenderer::set_frame_uniforms(const Scene& scene) {
  TraceUniforms& u = uniforms_;
  const Environment& env = scene.environment;
  bool textured = !env.texture.empty();
  u.env_color = textured ? glm::vec3(env.intensity) : env.color * env.intensity;
  u.env_textured = textured ? 1 : 0;
  u.env_rotation = glm::radians(env.rotation_deg);
  u.max_bounces = scene.render.max_bounces;
  const long per_sample =
      use_bvh_ ? bvh_loop_iterations_per_sample(bvh_max_steps(kBvhMaxLeafSize, scene.render.max_bounces),
                                                kBvhMaxLeafSize, scene.render.max_bounces)
               : loop_iterations_per_sample(shape_count_, scene.render.max_bounces);
  samples_per_draw_ = samples_per_draw_for(per_sample);
  exceeds_loop_limit_ = per_sample > kLlvmpipeLoopLimit;
  u.use_bvh = use_bvh_ ? 1 : 0;
  // The step cap matters on llvmpipe only (its loop limit); elsewhere it is a generous bound
  // that only a pathological tree would reach. Draws are split the same way everywhere.
  u.bvh_max_steps = llvmpipe_ ? bvh_max_steps(kBvhMaxLeafSize, scene.render.max_bounces) : kMaxBvhSteps;
  bvh_stats_.max_steps = u.bvh_max_steps;
  u.light_count = options_.light_sampling ? light_count_ : 0;
  // Shadow rays go to an environment map (importance-sampled) half of the time when there are
  // also emitting shapes; a constant environment is left to BSDF sampling (cosine-weighted
  // sampling of a constant is already as good as it gets for matte surfaces).
  const bool env_lights = options_.environment_sampling && textured && env.intensity > 0;
  u.env_select = env_lights ? (u.light_count > 0 ? 0.5f : 1.0f) : 0.0f;
  u.russian_roulette = options_.russian_roulette ? 1 : 0;
  u.clamp = options_.clamp;
  u.restart_together = restart_paths_together(options_.restart, env) ? 1 : 0;
  u.sobol = options_.sampler == SamplerKind::sobol ? 1 : 0;
  u.seed = static_cast<unsigned>(scene.render.seed);
  u.first_sample = options_.first_sample;
  float aspect = height_ > 0 ? static_cast<float>(width_) / static_cast<float>(height_) : 1.0f;
  gpu::CameraFrame cam = make_camera_frame(scene.camera, aspect);
  u.cam_origin = glm::vec3(glm::dvec3(scene.camera.position) - origin_);
  u.cam_right = cam.right;
  u.cam_up = cam.up;
  u.cam_forward = cam.forward;
  u.cam_tan_half_vfov = cam.tan_half_vfov;
  u.cam_aspect = cam.aspect;
  u.cam_aperture = cam.aperture;
  u.cam_focus = cam.focus;
}

// Every pass: the programs do not share uniform state, and a pass may use a different one than
// the last. A score of glProgramUniform calls is nothing next to a trace pass.
void GpuRenderer::apply_trace_uniforms(GlProgram& p, const TraceUniforms& u) {
  p.set("u_env_color", u.env_color);
  p.set("u_env_textured", u.env_textured);
  p.set("u_env_rotation", u.env_rotation);
  p.set("u_max_bounces", u.max_bounces);
  p.set("u_light_count", u.light_count);
  p.set("u_env_select", u.env_select);
  p.set("u_env_distribution_size", u.env_distribution_size);
  p.set("u_russian_roulette", u.russian_roulette);
  p.set("u_clamp", u.clamp);
  p.set("u_restart_together", u.restart_together);
  p.set("u_sobol", u.sobol);
  p.set("u_seed", u.seed);
  p.set("u_first_sample", u.first_sample);
  p.set("u_sphere_count", u.sphere_count);
  p.set("u_quad_count", u.quad_count);
  p.set("u_use_bvh", u.use_bvh);
  p.set("u_bvh_max_steps", u.bvh_max_steps);
  p.set("u_cam_origin", u.cam_origin);
  p.set("u_cam_right", u.cam_right);
  p.set("u_cam_up", u.cam_up);
  p.set("u_cam_forward", u.cam_forward);
  p.set("u_cam_tan_half_vfov", u.cam_tan_half_vfov);
  p.set("u_cam_aspect", u.cam_aspect);
  p.set("u_cam_aperture", u.cam_aperture);
  p.set("u_cam_focus", u.cam_focus);
}

// The exact variant for the scene's features if it is ready, else a ready one that covers
// them (e.g. the previous scene's after a feature was removed), else the generic program.
// Never waits for a compile.
GlProgram& GpuRenderer::choose_trace_program() {
  last_pass_defines_.clear();
  if (renderer_options_.force_generic_shader) return *trace_program_;
  const std::string wanted = variant_defines();
  if (wanted.empty()) return *trace_program_;
  auto best = variants_.end();
  for (auto it = variants_.begin(); it != variants_.end(); ++it) {
    poll_variant(*it);
    if (!it->ready || it->failed || !covers(it->features, features_)) continue;
    if (it->defines == wanted) {
      best = it;
      break;
    }
    if (best == variants_.end()) best = it;
  }
  if (best == variants_.end()) return *trace_program_;
  variants_.splice(variants_.begin(), variants_, best);  // most recently used
  last_pass_defines_ = best->defines;
  return *best->program;
}

std::string GpuRenderer::variant_defines() const {
  std::string defines = shader_defines(features_);
  return defines.empty() ? defines : defines + renderer_options_.extra_defines;
}

void GpuRenderer::poll_variant(Variant& v) {
  if (v.ready || v.failed) return;
  if (v.job) {
    if (!v.job->done()) return;
    v.program = std::move(v.job->program);
    v.failed = !v.program;  // kept, so that it is not built again; the generic program renders
    v.ready = !v.failed;
    v.job.reset();
    return;
  }
  if (!v.program->ready()) return;
  try {
    v.program->finish();
    v.ready = true;
  } catch (const std::exception&) {
    v.failed = true;
  }
}

void GpuRenderer::prepare_specialised_program() {
  start_variant_if_missing();
  for (Variant& v : variants_)
    if (v.defines == variant_defines()) {
      while (v.job && !v.job->done()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      if (!v.job && !v.ready && !v.failed) {
        try {
          v.program->finish();
          v.ready = true;
        } catch (const std::exception&) {
          v.failed = true;
        }
      }
      poll_variant(v);
    }
  warm_up_trace_program();
}

// A job for the worker: link the variant, then draw one pixel with it in the state a trace pass
// draws in (four RGBA32F targets; this renderer's textures on units 0-6 and buffers on 0-7, whose
// formats and sampling enter the compiled code's key), so that the driver compiles there the
// code this renderer's first pass will look up. The names are captured now; should the renderer
// replace a texture meanwhile, the driver compiles again at that first pass (only slower).
std::shared_ptr<ProgramJob> GpuRenderer::submit_variant_job(const std::string& defines) {
  auto job = std::make_shared<ProgramJob>();
  const bool compute = renderer_options_.backend == TraceBackend::compute;
  if (compute) {
    job->compute = "trace.comp";
    job->defines = work_group_defines(renderer_options_.work_group) + defines;
  } else {
    job->vertex = "fullscreen.vert";
    job->fragment = "trace.frag";
    job->defines = defines;
  }
  const TraceUniforms uniforms = uniforms_;
  const GLuint textures[7] = {accumulation_[current_], texel_textures_[0], environment_texture_,
                              compensation_[current_], texel_textures_[1], variance_[current_],
                              variance_compensation_[current_]};
  std::vector<GLuint> tables(table_textures_, table_textures_ + kTables);
  const GLuint loop_shapes = loop_shapes_buffer_;
  job->warm_up = [uniforms, textures, tables, loop_shapes, compute](GlProgram& p) {
    apply_trace_uniforms(p, uniforms);
    p.set("u_resolution", glm::ivec2(1, 1));
    p.set("u_samples_before", 0u);
    p.set("u_samples_per_pass", 0);
    for (GLuint i = 0; i < 7; ++i) glBindTextureUnit(i, textures[i]);
    for (GLuint k = 0; k < tables.size(); ++k) glBindTextureUnit(kTableUnit + k, tables[k]);
    glBindBufferBase(GL_UNIFORM_BUFFER, kLoopShapesBinding, loop_shapes);
    if (compute) {
      warm_up_compute_pass();
      return;
    }
    // Framebuffers are not shared between contexts: a 1x1 one like accumulation_fbo_, here.
    GLuint target[4];
    for (GLuint& t : target) t = make_texture_2d(GL_RGBA32F, 1, 1);
    GLuint fbo = make_trace_framebuffer({target[0], target[1], target[2], target[3]});
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(4, target);
  };
  renderer_options_.worker->submit(job);
  return job;
}

void GpuRenderer::start_variant_if_missing() {
  if (renderer_options_.force_generic_shader) return;
  std::string wanted = variant_defines();
  if (wanted.empty()) return;
  for (const Variant& v : variants_)
    if (v.defines == wanted) return;
  // Evict the least recently used; a compile still running is evicted like any other.
  if (variants_.size() >= kMaxVariants) variants_.pop_back();
  Variant v;
  v.features = features_;
  v.defines = wanted;
  if (renderer_options_.worker)
    v.job = submit_variant_job(wanted);
  else
    v.program = start_trace_program(renderer_options_.backend, renderer_options_.work_group, wanted);
  variants_.push_back(std::move(v));
}

// Binds `p`, buffers and textures for a draw that adds `samples` samples to pixels that have
// `samples_before` (u_samples_before) at adaptive sampling's pass `pass_index`: from buffer
// `source` into the other one (fragment), or in place (compute).
GlProgram& GpuRenderer::bind_trace_pass(GlProgram& p, int samples, int64_t samples_before,
                                        int64_t pass_index, int source) {
  apply_trace_uniforms(p, uniforms_);
  p.set("u_resolution", glm::ivec2(width_, height_));
  p.set("u_samples_before", static_cast<unsigned>(samples_before));
  p.set("u_samples_per_pass", samples);
  p.set("u_adaptive", options_.adaptive ? 1 : 0);
  p.set("u_adaptive_threshold", adaptive_threshold_);
  p.set("u_adaptive_min_samples", static_cast<unsigned>(std::max(2, options_.adaptive_min_samples)));
  p.set("u_adaptive_every", static_cast<unsigned>(std::max(1, options_.adaptive_every)));
  p.set("u_pass_index", static_cast<unsigned>(pass_index));
  glUseProgram(p.id());
  for (GLuint k = 0; k < kTables; ++k) glBindTextureUnit(kTableUnit + k, table_textures_[k]);
  glBindBufferBase(GL_UNIFORM_BUFFER, kLoopShapesBinding, loop_shapes_buffer_);
  glBindTextureUnit(1, texel_textures_[0]);
  glBindTextureUnit(2, environment_texture_);
  glBindTextureUnit(4, texel_textures_[1]);
  if (renderer_options_.backend == TraceBackend::compute) {
    bind_trace_images(targets(0));
    return p;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, accumulation_fbo_[1 - source]);
  glViewport(0, 0, width_, height_);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_SCISSOR_TEST);
  glBindTextureUnit(0, accumulation_[source]);
  glBindTextureUnit(3, compensation_[source]);
  glBindTextureUnit(5, variance_[source]);
  glBindTextureUnit(6, variance_compensation_[source]);
  glBindVertexArray(vao_);
  return p;
}

// One pixel of the spare buffer, no samples (it is overwritten by the next pass): a driver that
// compiles at the first draw (Mesa's llvmpipe JITs then, 0.6-1 s) does it here, not inside the
// first timed pass. The compute path has no spare buffer: one group with a resolution of 0x0,
// whose invocations all return before touching the images. Not while a pass is under way (its
// rows already traced are in the spare buffer).
void GpuRenderer::warm_up_trace_program() {
  if (width_ <= 0 || pass_under_way()) return;
  GlProgram& p = bind_trace_pass(choose_trace_program(), 0, samples_, passes_, current_);
  if (renderer_options_.backend == TraceBackend::compute) {
    p.set("u_resolution", glm::ivec2(0, 0));
    glDispatchCompute(1, 1, 1);
    glFinish();
    return;
  }
  glViewport(0, 0, 1, 1);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glFinish();
}

void GpuRenderer::trace(int samples) {
  begin_pass(samples);
  trace_rows(height_);
}

void GpuRenderer::begin_pass(int samples) {
  if (pass_under_way()) throw std::logic_error("a trace pass is already under way");
  if (samples <= 0 || width_ <= 0) return;
  // Adaptive sampling compares each pixel with the image's mean error per sample, refreshed
  // from the pixels' minimum on whenever the sample count has grown by a quarter (a small
  // read-back that waits for the GPU, renderer/error_estimate.h: O(log n) of them per render,
  // at sample counts that do not depend on the batches' timing).
  if (options_.adaptive && samples_ >= std::max(2, options_.adaptive_min_samples) &&
      samples_ * 4 >= threshold_samples_ * 5) {
    adaptive_threshold_ = static_cast<float>(estimate_error().relmse_per_sample);
    threshold_samples_ = samples_;
  }
  pass_.samples = samples;
  pass_.next_row = 0;
  pass_.program = &choose_trace_program();
}

// Each draw of the pass over rows [first, last): a pixel depends on its own previous state
// only, so a band may take all of the pass's draws before the next band starts. The fragment
// path alternates buffers from draw to draw; every band takes the same number of draws, so all
// end in the same buffer.
int GpuRenderer::trace_rows(int rows) {
  if (!pass_under_way()) return 0;
  const int first = pass_.next_row;
  const int last = std::min(height_, first + std::max(1, rows));
  const bool compute = renderer_options_.backend == TraceBackend::compute;
  collect_trace_timers(false);  // finished ones only, so the editor's list stays short
  // GL_TIMESTAMP pairs, not GL_TIME_ELAPSED: Mesa 22's llvmpipe returns the time since boot for
  // a context's first GL_TIME_ELAPSED query, and a pair never clashes with a caller's own query.
  GLuint timer[2] = {0, 0};
  glCreateQueries(GL_TIMESTAMP, 2, timer);
  glQueryCounter(timer[0], GL_TIMESTAMP);
  int source = current_;
  int draws = 0;
  for (int done = 0; done < pass_.samples; ++draws) {
    const int n = std::min(pass_.samples - done, samples_per_draw_);
    GlProgram& p = bind_trace_pass(*pass_.program, n, samples_ + done, passes_ + draws, source);
    if (compute) {
      p.set("u_tile_origin", glm::ivec2(0, first));
      p.set("u_tile_end", glm::ivec2(width_, last));
      dispatch_trace(width_, last - first, renderer_options_.work_group);
    } else {
      const bool whole = first == 0 && last == height_;
      if (!whole) {
        glEnable(GL_SCISSOR_TEST);
        glScissor(0, first, width_, last - first);  // window row y is texel row y
      }
      glDrawArrays(GL_TRIANGLES, 0, 3);
      glDisable(GL_SCISSOR_TEST);
      source = 1 - source;
    }
    if (aov_pass_) trace_aov_pass(n, samples_ + done, first, last - first);
    done += n;
  }
  glQueryCounter(timer[1], GL_TIMESTAMP);
  trace_timers_.insert(trace_timers_.end(), timer, timer + 2);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  pass_.next_row = last;
  if (last == height_) {
    current_ = source;
    samples_ += pass_.samples;
    passes_ += draws;
    pass_ = {};
    display_stale_ = true;
    // After the pass, so that a driver without parallel compilation (Mesa's llvmpipe links in
    // glLinkProgram) at least has this pass queued first.
    if (last_pass_generic()) start_variant_if_missing();
  }
  return last - first;
}

// Adds the passes whose timestamps are in (all of them when `wait`) to trace_gpu_seconds_.
// Queries finish in submission order, so the first unfinished pass ends the scan.
void GpuRenderer::collect_trace_timers(bool wait) {
  size_t done = 0;
  for (; done + 1 < trace_timers_.size(); done += 2) {
    GLint available = 0;
    if (!wait) glGetQueryObjectiv(trace_timers_[done + 1], GL_QUERY_RESULT_AVAILABLE, &available);
    if (!wait && !available) break;
    GLuint64 begin = 0, end = 0;
    glGetQueryObjectui64v(trace_timers_[done], GL_QUERY_RESULT, &begin);
    glGetQueryObjectui64v(trace_timers_[done + 1], GL_QUERY_RESULT, &end);
    trace_gpu_seconds_ += end > begin ? static_cast<double>(end - begin) * 1e-9 : 0.0;
  }
  if (done > 0) glDeleteQueries(static_cast<GLsizei>(done), trace_timers_.data());
  trace_timers_.erase(trace_timers_.begin(), trace_timers_.begin() + static_cast<std::ptrdiff_t>(done));
}

double GpuRenderer::trace_gpu_seconds() {
  collect_trace_timers(true);
  return trace_gpu_seconds_;
}

void GpuRenderer::update_display() {
  if (!display_stale_ || width_ <= 0) return;
  glBindFramebuffer(GL_FRAMEBUFFER, display_fbo_);
  glViewport(0, 0, width_, height_);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_SCISSOR_TEST);
  glUseProgram(tonemap_program_->id());
  glBindTextureUnit(0, accumulation_[current_]);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  display_stale_ = false;
}

Image GpuRenderer::read_accumulation() const {
  Image image;
  image.width = width_;
  image.height = height_;
  image.pixels.assign(static_cast<size_t>(width_) * height_ * 4, 0.0f);
  if (samples_ > 0)
    glGetTextureImage(accumulation_[current_], 0, GL_RGBA, GL_FLOAT,
                      static_cast<GLsizei>(image.pixels.size() * sizeof(float)), image.pixels.data());
  return image;
}

ErrorEstimate GpuRenderer::estimate_error() {
  if (estimate_samples_ == samples_) return estimate_;
  estimate_ = samples_ > 0 ? estimator_->estimate(accumulation_[current_], compensation_[current_],
                                                  variance_[current_], width_, height_)
                           : ErrorEstimate{};
  estimate_samples_ = samples_;
  return estimate_;
}

Image GpuRenderer::read_variance() const {
  Image image;
  image.width = width_;
  image.height = height_;
  const size_t n = static_cast<size_t>(width_) * height_ * 4;
  image.pixels.assign(n, 0.0f);
  if (samples_ <= 0) return image;
  const GLsizei bytes = static_cast<GLsizei>(n * sizeof(float));
  glGetTextureImage(variance_[current_], 0, GL_RGBA, GL_FLOAT, bytes, image.pixels.data());
  std::vector<float> compensation(n);
  glGetTextureImage(compensation_[current_], 0, GL_RGBA, GL_FLOAT, bytes, compensation.data());
  for (size_t i = 3; i < n; i += 4) image.pixels[i] = compensation[i];
  return image;
}

void GpuRenderer::set_aovs_enabled(bool enabled) {
  if (!enabled) {
    aov_pass_.reset();
    return;
  }
  if (aov_pass_) return;
  aov_pass_ = std::make_unique<AovPass>();
  aov_pass_->resize(width_, height_);
}

// The same samples as the colour draw just made, over the same rows, with the scene's buffers
// and textures as bind_trace_pass left them.
void GpuRenderer::trace_aov_pass(int samples, int64_t samples_before, int first_row, int rows) {
  GlProgram& p = aov_pass_->program();
  apply_trace_uniforms(p, uniforms_);
  p.set("u_samples_before", static_cast<unsigned>(samples_before));
  p.set("u_samples_per_pass", samples);
  aov_pass_->draw(first_row, rows);
}

AovImages GpuRenderer::read_aovs() const {
  if (!aov_pass_) return {};
  return aov_pass_->read();
}

Image GpuRenderer::read_display() {
  update_display();
  Image image;
  image.width = width_;
  image.height = height_;
  image.pixels.resize(static_cast<size_t>(width_) * height_ * 4);
  glGetTextureImage(display_texture_, 0, GL_RGBA, GL_FLOAT,
                    static_cast<GLsizei>(image.pixels.size() * sizeof(float)), image.pixels.data());
  return image;
}

void save_render(GpuRenderer& renderer, const std::filesystem::path& file) {
  Image image;
  if (file.extension() == ".png") {
    image = renderer.read_display();
  } else {
    image = renderer.read_accumulation();  // alpha holds the discarded-sample count
    for (size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 1.0f;
  }
  save_image(file, image);
}

}  // namespace glint
