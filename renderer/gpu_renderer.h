// The progressive GPU path tracer (docs/DESIGN.md §3). Runs in any current OpenGL 4.5 core
// context.
//
// Per frame: sync(scene) compares digests and uploads only what changed, restarting the
// accumulation when radiance inputs changed; trace(k) adds k samples per pixel, with the
// fragment shader into ping-pong RGBA32F buffers or with the compute shader in place
// (renderer/trace_backend.h); update_display() re-runs the tonemap pass when its inputs
// changed. The running mean is kept with Kahan compensation (a second RGBA32F texture;
// shaders/trace_common.glsl) so that 10^5 passes do not drift it (tests/soak, bench/reports/SOAK.md),
// and beside it each pixel's variance (two more), from which estimate_error() tells the
// image's expected error without a reference (renderer/error_estimate.h).
//
// A facade over the units that do the work: the film (renderer/film_buffers.h), the scene's
// tables, textures and BVH (scene_tables.h, scene_textures.h, bvh_tables.h), the trace uniforms
// (trace_uniforms.h), the cache of specialised programs (program_variants.h), the draws of a pass
// (trace_draws.h) and their GPU timers (trace_timers.h). Final images are written by
// renderer/render_output.h.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <epoxy/gl.h>

#include "renderer/aov_pass.h"
#include "renderer/bvh_tables.h"
#include "renderer/error_estimate.h"
#include "renderer/error_map.h"
#include "renderer/film_buffers.h"
#include "renderer/image.h"
#include "renderer/program_variants.h"
#include "renderer/render_options.h"
#include "renderer/sample_region.h"
#include "renderer/scene.h"
#include "renderer/scene_digest.h"
#include "renderer/scene_tables.h"
#include "renderer/scene_textures.h"
#include "renderer/shader_features.h"
#include "renderer/trace_backend.h"
#include "renderer/trace_draws.h"
#include "renderer/trace_timers.h"
#include "renderer/trace_uniforms.h"

namespace glint {

class GlProgram;

struct SyncResult {
  bool accumulation_reset = false;  // radiance inputs or the resolution changed
  bool display_changed = false;     // exposure or tonemap changed (no reset on its own)
};

class ProgramWorker;
struct ProgramJob;

enum class MneeChoice { automatic, always, never };

struct GpuRendererOptions {
  // Which entry point traces (same image; renderer/backend_choice.h picks the faster one).
  TraceBackend backend = TraceBackend::fragment;
  WorkGroup work_group;  // of the compute shader
  // Always trace with the generic program (every feature compiled in): for measurements.
  bool force_generic_shader = false;
  // Manifold next-event estimation (renderer/mnee_casters.h): automatic, in the programs of
  // scenes where it pays off, for the lights where it does (mnee_lights); always, in those of
  // every scene that needs it, for every light it can sample;
  // never, the path tracer alone. The same image in expectation either way.
  MneeChoice mnee = MneeChoice::automatic;
  // Where specialised programs are built (renderer/program_worker.h): off the calling thread,
  // in a shared context, with the driver's first-draw compile done there too. Without one they
  // are built in this context with GL_KHR_parallel_shader_compile where the driver has it.
  std::shared_ptr<ProgramWorker> worker;
  // Appended to every specialised program's defines. Tests put a nonce here, so that the
  // driver's shader cache has never seen the program and its compile is really timed.
  std::string extra_defines;
  // Texels the textures of one kind (8-bit, float) may hold together; 0 for the driver's limit
  // (kTexelRowWidth x GL_MAX_TEXTURE_SIZE). Tests set a small one to reach the refusal.
  int64_t max_texture_texels = 0;
  // Texels a scene table may hold (spheres take 2 each, quads 8); 0 for the driver's limit
  // (GL_MAX_TEXTURE_BUFFER_SIZE). Tests set a small one to reach the refusal.
  int64_t max_table_texels = 0;
};

class GpuRenderer {
 public:
  // Texels per row of the colour textures that hold the textures' texels (scene_textures.h).
  static constexpr int kTexelRowWidth = glint::kTexelRowWidth;
  // Compiles the generic trace program and the tonemap program; throws std::runtime_error
  // with the driver's log. Programs specialised to a scene's ShaderFeatures are compiled
  // later, when a scene needs them (see trace()).
  explicit GpuRenderer(GpuRendererOptions options = {});
  ~GpuRenderer();
  GpuRenderer(const GpuRenderer&) = delete;
  GpuRenderer& operator=(const GpuRenderer&) = delete;

  // Brings the GPU state up to date with a validated scene rendered at width x height.
  // Throws ImageError if a texture cannot be loaded or the driver cannot hold the textures
  // (the message names the JSON path, e.g. textures[2].path, and the limit), and
  // std::runtime_error for a size beyond a project's film limits (check_film_size); the
  // previous state is then kept.
  SyncResult sync(const Scene& scene, int width, int height);

  // Takes effect at the next sync, which then restarts the accumulation if they changed.
  void set_options(const RenderOptions& options) { options_ = options; }

  // Region render: from the next pass only the pixels of `region` (clipped to the film) take
  // samples; the others keep what they hold. No reset: a region drawn over a running preview
  // refines its part of the image. nullopt: every pixel again (each continues from its own
  // count). The region does not apply to a pass already under way.
  void set_sample_region(const std::optional<PixelRect>& region) { region_ = region; }
  const std::optional<PixelRect>& sample_region() const { return region_; }
  const RenderOptions& options() const { return options_; }

  // Adds `samples` samples to every pixel in one pass, with the specialised program for the
  // scene's features if it is compiled, otherwise with the generic one. A pass that finds no
  // program for the current features issues its compile after the pass: on the worker if
  // there is one, else here (non-blocking where the driver compiles in parallel); later passes
  // switch to it once it is ready. Both programs draw the same random numbers and give the
  // same image.
  void trace(int samples);

  // A pass traced in parts, for a caller that bounds the GPU work of each call (the editor's
  // export; docs/DESIGN.md §5.2, Tiled passes): begin_pass(samples) starts it, each trace_rows()
  // traces the next band of image rows, and the call that traces the last row ends it. Every
  // pixel gets the draws that trace(samples) gives it, from one program chosen at the start, so
  // the image is the same. Everything else sees the pass as one unit, at its end: sample_count(),
  // the display, the error estimate, adaptive sampling's pass index, the switch to a specialised
  // program. The fragment path draws each band (glScissor) into the spare buffer and swaps at the
  // end; the compute path writes each band in place, so until the pass ends its accumulation
  // holds some rows with the pass's samples and some without: read the images (read_*,
  // estimate_error, update_display) between passes only. A sync that resets the accumulation
  // abandons the pass. Throws std::logic_error if a pass is already under way; does nothing
  // for samples <= 0 or an empty film.
  void begin_pass(int samples);
  // Traces the next min(rows, pass_rows_left()) rows (at least one) of the pass under way, in
  // one call's worth of draws (one per loop_budget.h's draw limit); returns the rows traced, 0
  // with no pass under way. Never waits for the GPU.
  int trace_rows(int rows);
  bool pass_under_way() const { return pass_.samples > 0; }
  int pass_samples() const { return pass_.samples; }  // per pixel, of the pass under way
  int pass_rows_left() const { return pass_under_way() ? film_.height() - pass_.next_row : 0; }

  // For batch renders (`glint render`): compiles the program specialised to the synced scene
  // now, waiting for it, so that no pass is spent on the generic one, and draws one pixel with
  // the program that will run (generic with force_generic_shader or when the scene needs every
  // feature) so that a driver's compile-at-first-draw happens before the clock starts.
  void prepare_specialised_program();

  // What the synced scene needs, and the defines of the program that ran the last trace pass
  // ("" for the generic program; shader_defines(features()) + extra_defines once specialised).
  const ShaderFeatures& features() const { return features_; }
  const std::string& last_pass_defines() const { return last_pass_defines_; }
  bool last_pass_generic() const { return last_pass_defines_.empty(); }

  // Re-runs the tonemap pass if the accumulation or the display settings changed since the
  // last run. Never touches the accumulation.
  void update_display();

  // Samples per pixel traced since the accumulation was reset; with adaptive sampling
  // (RenderOptions::adaptive) the most any pixel has taken.
  int64_t sample_count() const { return samples_; }
  // The estimated relMSE of the accumulation (renderer/error_estimate.h): a few small draws
  // and a read-back of at most 32x32 sums, waiting for the passes in flight; cached until the
  // next pass.
  ErrorEstimate estimate_error();
  // GPU time of the trace passes since the accumulation was last reset, from GL_TIMESTAMP
  // queries around each pass. Waits for passes still in flight; trace() itself never waits.
  double trace_gpu_seconds();
  // One sample of the synced scene may run more loop iterations than Mesa's llvmpipe allows
  // a shader invocation (renderer/loop_budget.h): on llvmpipe its image would be wrong.
  bool exceeds_llvmpipe_loop_limit() const { return draw_split_.exceeds_loop_limit; }
  // Whether closest hits of the synced scene are found with the BVH (use_bvh in bvh.h), and the
  // hierarchy's last update: a full build, or a refit when only shapes moved (an editor drag).
  bool uses_bvh() const { return use_bvh_; }
  using BvhStats = glint::BvhStats;
  const BvhStats& bvh_stats() const { return bvh_.stats(); }
  TraceBackend backend() const { return renderer_options_.backend; }
  int width() const { return film_.width(); }
  int height() const { return film_.height(); }
  GLuint display_texture() const { return film_.display_texture(); }

  // Mean linear radiance per pixel (rgb) and the count of discarded non-finite samples (a).
  Image read_accumulation() const;
  // Each pixel's mean squared deviation of its finite samples (rgb) and the samples it has
  // taken (a; below sample_count() only with adaptive sampling).
  Image read_variance() const;
  // Each pixel's coverage in [0, 1] (rgb and a alike): the fraction of its finite samples whose
  // camera ray hit a surface rather than the environment; 0 for a pixel without samples.
  Image read_coverage() const;

  // The auxiliary images for the denoiser (renderer/aov_pass.h): when enabled, every trace pass
  // adds the same samples to them; enabling starts them empty, an accumulation reset clears
  // them. Off by default (the pass costs a camera ray and a hit per sample).
  void set_aovs_enabled(bool enabled);
  bool aovs_enabled() const { return aov_pass_ != nullptr; }
  AovImages read_aovs() const;  // empty images when disabled
  // The live error map of the latest accumulation (renderer/error_map.h): an RGBA8 texture of
  // the film's size, drawn again only when the accumulation changed since the last call (0 for
  // an empty film). Between passes only, as the other read-outs.
  GLuint error_map();

  // The tonemapped display image in [0,1] (calls update_display first).
  Image read_display();

 private:
  // sync()'s parts: the uploads of what changed (images first), then the features.
  void upload_changes(const Scene& scene, const SceneDigests& d);
  void update_features(const Scene& scene, const SceneDigests& d, bool geometry_changed);
  void reset_accumulation();
  TraceBindings bindings() const {
    return {uniforms_, tables_, textures_, film_, vao_, renderer_options_.backend, renderer_options_.work_group};
  }
  AdaptiveUniforms adaptive_uniforms() const;
  std::unique_ptr<ProgramBuild> start_variant_build(const std::string& defines);
  std::string variant_defines() const;  // the cache key of the synced scene's variant
  GlProgram& choose_trace_program();
  void start_variant_if_missing();
  void warm_up_trace_program();

  GpuRendererOptions renderer_options_;
  std::unique_ptr<GlProgram> trace_program_;  // the generic one
  ProgramVariants variants_;
  ShaderFeatures features_;
  std::string last_pass_defines_;
  TraceUniforms uniforms_;
  FilmBuffers film_;
  std::unique_ptr<ErrorEstimator> estimator_;
  std::unique_ptr<AovPass> aov_pass_;  // while AOVs are enabled
  std::unique_ptr<ErrorMap> error_map_;  // from the first error_map() on
  int64_t accumulation_version_ = 0;     // counts passes and resets
  int64_t error_map_version_ = -1;       // accumulation_version_ the map shows
  GLuint error_map_texture_ = 0;         // owned by error_map_
  GLuint vao_ = 0;
  bool llvmpipe_ = false;  // the context is Mesa's llvmpipe (its loop limit applies)
  SceneTables tables_;
  SceneTextures textures_;
  BvhTables bvh_;
  TraceTimers timers_;

  // The pass begun by begin_pass (trace() is one of them, traced in one band).
  struct Pass {
    int samples = 0;    // per pixel; 0: none under way
    int next_row = 0;   // rows [0, next_row) are traced
    GlProgram* program = nullptr;  // the generic one or a variant's, never evicted meanwhile
  };
  Pass pass_;
  int64_t samples_ = 0;
  int64_t passes_ = 0;             // draws since the reset (adaptive sampling's pass index)
  float adaptive_threshold_ = 0;   // the image's mean error per sample at the last estimate
  int64_t threshold_samples_ = 0;  // sample_count() when adaptive_threshold_ was taken
  ErrorEstimate estimate_;
  int64_t estimate_samples_ = -1;  // sample_count() when estimate_ was taken
  bool first_sync_ = true;
  SceneDigests digests_;
  RenderOptions options_;
  RenderOptions synced_options_;
  glm::dvec3 origin_{0};  // render_origin of the packed scene
  GeometryCounts counts_;
  DrawSplit draw_split_;
  bool use_bvh_ = false;
  std::optional<PixelRect> region_;
  bool per_pixel_counts_ = false;  // a pass since the reset had a region: counts may differ
};

}  // namespace glint
