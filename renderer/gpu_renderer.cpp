#include "renderer/gpu_renderer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "renderer/gl_context.h"
#include "renderer/gl_program.h"
#include "renderer/gpu_scene.h"
#include "renderer/llvmpipe_threads.h"
#include "renderer/loop_budget.h"
#include "renderer/mnee_casters.h"
#include "renderer/program_worker.h"
#include "renderer/scene_validation.h"

namespace glint {
namespace {

std::unique_ptr<GlProgram> generic_trace_program(const GpuRendererOptions& options) {
  auto program = start_trace_program(options.backend, options.work_group, "");
  program->finish();
  return program;
}

}  // namespace

GpuRenderer::GpuRenderer(GpuRendererOptions options)
    : renderer_options_(options),
      trace_program_(generic_trace_program(options)),
      variants_([this](const std::string& defines) { return start_variant_build(defines); }),
      film_(options.backend),
      estimator_(std::make_unique<ErrorEstimator>()),
      tables_(options.max_table_texels),
      textures_(options.max_texture_texels) {
  glCreateVertexArrays(1, &vao_);
  llvmpipe_ = on_llvmpipe();
  // One CPU per llvmpipe thread, so that short passes use every CPU (llvmpipe_threads.h).
  if (llvmpipe_) pin_llvmpipe_threads();
}

GpuRenderer::~GpuRenderer() {
  estimator_.reset();
  glDeleteVertexArrays(1, &vao_);
}

SyncResult GpuRenderer::sync(const Scene& scene, int width, int height) {
  // The film limits of a project hold for every caller (and before anything changes): a
  // larger image would fail to allocate, or crash the driver, only after gigabytes.
  if (width > 0 && height > 0)
    if (const auto problem = check_film_size(width, height))
      throw std::runtime_error("cannot render a " + std::to_string(width) + "x" +
                               std::to_string(height) + " image: " + problem->what());
  const SceneDigests d = digest_scene(scene);
  upload_changes(scene, d);
  SyncResult result;
  if (width != film_.width() || height != film_.height()) {
    film_.resize(width, height);
    if (aov_pass_ && !film_.empty()) aov_pass_->resize(width, height);
    result.accumulation_reset = true;
  }
  if (first_sync_ || d.radiance() != digests_.radiance() || options_ != synced_options_)
    result.accumulation_reset = true;
  if (result.accumulation_reset) {  // the aspect ratio may have changed
    draw_split_ = draw_split(static_cast<long>(counts_.spheres) + counts_.quads,
                             loop_budget_bounces(scene.render.max_bounces, features_.mnee), use_bvh_);
    set_frame_uniforms(uniforms_, scene, options_,
                       {counts_.lights, use_bvh_, llvmpipe_, origin_, film_.width(), film_.height(), features_.mnee});
    bvh_.set_max_steps(uniforms_.bvh_max_steps);
  }
  if (first_sync_ || d.display != digests_.display) {
    film_.set_display_settings(scene.display);
    result.display_changed = true;
  }
  if (result.accumulation_reset) reset_accumulation();
  digests_ = d;
  synced_options_ = options_;
  first_sync_ = false;
  return result;
}

void GpuRenderer::upload_changes(const Scene& scene, const SceneDigests& d) {
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
  if (first_sync_ || d.textures != digests_.textures || (geometry_changed && packed.layers != textures_.layers()))
    textures_.upload_textures(scene, packed.layers, tables_);
  if (first_sync_ || d.environment != digests_.environment)
    uniforms_.env_distribution_size = textures_.upload_environment(scene, tables_);
  if (geometry_changed) {
    counts_ = upload_geometry(tables_, packed);
    uniforms_.sphere_count = counts_.spheres;
    uniforms_.quad_count = counts_.quads;
    uniforms_.caster_count = static_cast<int>(packed.casters.size());
    std::copy(packed.casters.begin(), packed.casters.end(), uniforms_.casters.begin());
    bvh_.invalidate();  // refitted or rebuilt below if the BVH is used
    origin_ = origin;
  }
  use_bvh_ = use_bvh(options_.accel, static_cast<long>(scene.spheres.size() + scene.quads.size()),
                     scene.render.max_bounces);
  if (use_bvh_) {
    // The boxes are padded for ray origins up to the camera's distance from the render origin
    // (bvh.cpp): a camera beyond that needs wider boxes.
    const glm::vec3 camera(glm::dvec3(scene.camera.position) - origin_);
    const float camera_extent = std::max({std::abs(camera.x), std::abs(camera.y), std::abs(camera.z)});
    if (!bvh_.fits(camera_extent)) {
      if (!geometry_changed) packed = pack_scene(scene, origin_);
      bvh_.update(packed, camera, tables_);
    }
  }
  update_features(scene, d, geometry_changed);
}

void GpuRenderer::update_features(const Scene& scene, const SceneDigests& d, bool geometry_changed) {
  // The texture alpha probe only when what it depends on changed; the lens is cheap.
  if (geometry_changed || first_sync_ || d.textures != digests_.textures ||
      d.environment != digests_.environment)
    features_ = scene_features(scene);
  uniforms_.mnee_lights = renderer_options_.mnee == MneeChoice::never
                             ? 0
                             : mnee_lights(scene, textures_.environment_peak_share(),
                                           renderer_options_.mnee == MneeChoice::always);
  features_.mnee = features_.mnee && uniforms_.mnee_lights != 0;
  features_.thin_lens = scene.camera.aperture_radius > 0;
  features_.loop_traversal = !use_bvh_;
  features_.bvh_traversal = use_bvh_;
  features_.sobol_sampler = options_.sampler == SamplerKind::sobol;
  features_.pcg_sampler = !features_.sobol_sampler;
  features_ = with_loop_counts(features_, static_cast<long>(scene.spheres.size()),
                               static_cast<long>(scene.quads.size()));
}

void GpuRenderer::reset_accumulation() {
  pass_ = {};  // a pass under way is abandoned
  samples_ = 0;
  passes_ = 0;
  threshold_samples_ = 0;
  adaptive_threshold_ = 0;
  estimate_ = {};
  estimate_samples_ = -1;
  timers_.reset();
  film_.clear();
  if (aov_pass_) aov_pass_->clear();
  per_pixel_counts_ = false;
  ++accumulation_version_;
}

AdaptiveUniforms GpuRenderer::adaptive_uniforms() const {
  AdaptiveUniforms u{options_.adaptive, adaptive_threshold_, options_.adaptive_min_samples,
                     options_.adaptive_every};
  if (region_ && !region_->empty()) {
    u.region_on = true;
    u.region = {region_->x0, region_->y0, region_->x1, region_->y1};
  }
  u.per_pixel_counts = per_pixel_counts_;
  return u;
}

// The exact variant for the scene's features if it is ready, else a ready one that covers
// them (e.g. the previous scene's after a feature was removed), else the generic program.
// Never waits for a compile.
GlProgram& GpuRenderer::choose_trace_program() {
  last_pass_defines_.clear();
  if (renderer_options_.force_generic_shader) return *trace_program_;
  const std::string wanted = variant_defines();
  if (wanted.empty()) return *trace_program_;
  GlProgram* variant = variants_.choose(features_, wanted, last_pass_defines_);
  return variant ? *variant : *trace_program_;
}

std::string GpuRenderer::variant_defines() const {
  std::string defines = shader_defines(features_);
  return defines.empty() ? defines : defines + renderer_options_.extra_defines;
}

// On the worker where there is one (its job also draws once), else in this context.
std::unique_ptr<ProgramBuild> GpuRenderer::start_variant_build(const std::string& defines) {
  if (!renderer_options_.worker)
    return context_build(start_trace_program(renderer_options_.backend, renderer_options_.work_group, defines));
  std::shared_ptr<ProgramJob> job = trace_variant_job(defines, bindings());
  renderer_options_.worker->submit(job);
  return worker_build(std::move(job));
}

void GpuRenderer::start_variant_if_missing() {
  if (renderer_options_.force_generic_shader) return;
  const std::string wanted = variant_defines();
  if (!wanted.empty()) variants_.start_if_missing(features_, wanted);
}

void GpuRenderer::prepare_specialised_program() {
  start_variant_if_missing();
  variants_.wait(variant_defines());
  warm_up_trace_program();
}

// Not while a pass is under way (its rows already traced are in the spare side).
void GpuRenderer::warm_up_trace_program() {
  if (film_.width() <= 0 || pass_under_way()) return;
  warm_up_trace_draw(choose_trace_program(), bindings(), adaptive_uniforms(),
                     {0, samples_, passes_, film_.latest()});
}

void GpuRenderer::trace(int samples) {
  begin_pass(samples);
  trace_rows(film_.height());
}

void GpuRenderer::begin_pass(int samples) {
  if (pass_under_way()) throw std::logic_error("a trace pass is already under way");
  if (samples <= 0 || film_.width() <= 0) return;
  // Adaptive sampling compares each pixel with the image's mean error per sample, refreshed
  // from the pixels' minimum on whenever the sample count has grown by a quarter (a small
  // read-back that waits for the GPU, renderer/error_estimate.h: O(log n) of them per render,
  // at sample counts that do not depend on the batches' timing).
  if (options_.adaptive && samples_ >= std::max(2, options_.adaptive_min_samples) &&
      samples_ * 4 >= threshold_samples_ * 5) {
    adaptive_threshold_ = static_cast<float>(estimate_error().relmse_per_sample);
    threshold_samples_ = samples_;
  }
  // From the first pass with a region on, pixels' counts may differ until the next reset.
  if (region_ && !region_->empty()) per_pixel_counts_ = true;
  pass_.samples = samples;
  pass_.next_row = 0;
  pass_.program = &choose_trace_program();
}

int GpuRenderer::trace_rows(int rows) {
  if (!pass_under_way()) return 0;
  const int first = pass_.next_row;
  const int last = std::min(film_.height(), first + std::max(1, rows));
  timers_.collect(false);  // finished ones only, so the editor's list stays short
  timers_.start();
  const BandResult band =
      trace_band(*pass_.program, bindings(), adaptive_uniforms(), {0, samples_, passes_, film_.latest()},
                 {pass_.samples, draw_split_.samples_per_draw, first, last}, aov_pass_.get());
  timers_.stop();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  pass_.next_row = last;
  if (last == film_.height()) {
    film_.set_latest(band.side);
    samples_ += pass_.samples;
    passes_ += band.draws;
    pass_ = {};
    film_.mark_display_stale();
    ++accumulation_version_;
    // After the pass, so that a driver without parallel compilation (Mesa's llvmpipe links in
    // glLinkProgram) at least has this pass queued first.
    if (last_pass_generic()) start_variant_if_missing();
  }
  return last - first;
}

double GpuRenderer::trace_gpu_seconds() {
  timers_.collect(true);
  return timers_.seconds();
}

void GpuRenderer::update_display() { film_.update_display(vao_); }

ErrorEstimate GpuRenderer::estimate_error() {
  if (estimate_samples_ == samples_) return estimate_;
  const TraceTargets t = film_.targets(film_.latest());
  estimate_ = samples_ > 0 ? estimator_->estimate(t.accumulation, t.compensation, t.variance, film_.width(),
                                                  film_.height())
                           : ErrorEstimate{};
  estimate_samples_ = samples_;
  return estimate_;
}

Image GpuRenderer::read_accumulation() const {
  return samples_ > 0 ? film_.read_accumulation() : Image::filled(film_.width(), film_.height(), 0.0f);
}

Image GpuRenderer::read_variance() const {
  return samples_ > 0 ? film_.read_variance() : Image::filled(film_.width(), film_.height(), 0.0f);
}

GLuint GpuRenderer::error_map() {
  if (film_.width() <= 0) return 0;
  if (!error_map_) error_map_ = std::make_unique<ErrorMap>();
  if (error_map_version_ == accumulation_version_ && error_map_texture_) return error_map_texture_;
  const TraceTargets t = film_.targets(film_.latest());
  error_map_texture_ = error_map_->draw(t.accumulation, t.compensation, t.variance, film_.width(), film_.height());
  error_map_version_ = accumulation_version_;
  return error_map_texture_;
}

Image GpuRenderer::read_coverage() const {
  return samples_ > 0 ? film_.read_coverage() : Image::filled(film_.width(), film_.height(), 0.0f);
}

Image GpuRenderer::read_display() {
  update_display();
  return film_.read_display();
}

void GpuRenderer::set_aovs_enabled(bool enabled) {
  if (!enabled) {
    aov_pass_.reset();
    return;
  }
  if (aov_pass_) return;
  aov_pass_ = std::make_unique<AovPass>();
  aov_pass_->resize(film_.width(), film_.height());
}

AovImages GpuRenderer::read_aovs() const {
  if (!aov_pass_) return {};
  return aov_pass_->read();
}

}  // namespace glint
