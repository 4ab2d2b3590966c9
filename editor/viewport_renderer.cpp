#include "editor/viewport_renderer.h"

#include <algorithm>
#include <cmath>

#include <epoxy/gl.h>

#include "editor/film_frame.h"
#include "renderer/gl_context.h"
#include "renderer/render_session.h"
#include "renderer/scene_validation.h"
#include "renderer/stopwatch.h"

namespace glint {

ViewportRenderer::ViewportRenderer(GpuRendererOptions options) : renderer_(std::move(options)) {}

namespace {

int fixed_divisor(ViewportResolution resolution) {
  switch (resolution) {
    case ViewportResolution::half: return 2;
    case ViewportResolution::quarter: return 4;
    default: return 1;
  }
}

}  // namespace

void ViewportRenderer::record_frame_time() {
  auto now = std::chrono::steady_clock::now();
  if (last_frame_.time_since_epoch().count() != 0) {
    double ms = std::chrono::duration<double, std::milli>(now - last_frame_).count();
    ms_per_frame_ = ms_per_frame_ > 0 ? 0.9 * ms_per_frame_ + 0.1 * ms : ms;
    budget_.record_frame(ms * 1e-3, last_trace_seconds_);
  }
  last_trace_seconds_ = 0;
  last_frame_ = now;
}

ViewportRenderer::Sync ViewportRenderer::sync_scene(const Scene& scene, const ViewportRequest& request,
                                                    FrameStats& stats) {
  // Trace at framebuffer pixels (HiDPI), divided down when the device is too slow for that.
  Sync sync;
  sync.full_w = std::max(1, request.width);
  sync.full_h = std::max(1, request.height);
  const bool automatic = request.resolution == ViewportResolution::automatic;
  sync.divisor = !automatic ? fixed_divisor(request.resolution)
                 : preview_.divisor() > 0 ? preview_.divisor() : budget_.divisor();
  auto trace_size = [&](int d) {
    return std::pair{std::max(1, (sync.full_w + d - 1) / d), std::max(1, (sync.full_h + d - 1) / d)};
  };
  auto [w, h] = trace_size(sync.divisor);

  // The viewport frames the export's film: its camera is widened when letterboxed.
  const Scene* traced = &scene;
  Scene framed;
  if (request.film_width > 0 && request.film_height > 0) {
    framed = scene;
    framed.camera = viewport_camera(scene.camera, glm::vec2(sync.full_w, sync.full_h),
                                    Film{request.film_width, request.film_height});
    traced = &framed;
  }

  // An invalid value typed into a field (a zero-area quad, say) keeps the last good image.
  auto problems = validate_scene(*traced, false);
  stats.scene_problem = problems.empty() ? "" : problems.front().what();
  if (!problems.empty()) return sync;
  try {
    renderer_.set_options(request.estimator);
    stats.restarted = renderer_.sync(*traced, w, h).accumulation_reset;
    if (stats.restarted) held_.release();  // an edit: the held image is out of date
    sync.synced = true;
    if (!automatic) return sync;
    // Fluid while editing, finer when idle; the level changes only here.
    sync.preview = {stats.restarted, request.user_active, seconds_since(start_), renderer_.sample_count(),
                    int64_t(sync.full_w) * sync.full_h};
    if (int d = preview_.update(budget_, sync.preview); d != sync.divisor) {
      if (d < sync.divisor && !stats.restarted) held_.keep(renderer_.display_texture());
      sync.divisor = d;
      std::tie(w, h) = trace_size(d);
      renderer_.sync(*traced, w, h);
      stats.restarted = true;
    }
  } catch (const std::exception& e) {
    stats.scene_problem = e.what();  // an unreadable image: previous state kept
  }
  return sync;
}

void ViewportRenderer::update_estimate(bool synced, bool restarted) {
  // The error estimate, a few times a second (for the status line and the target, which is
  // then overshot by at most that much tracing).
  if (restarted) estimated_relmse_ = -1;
  if (synced && renderer_.sample_count() >= 2 && !renderer_.pass_under_way() &&
      (estimated_relmse_ < 0 || seconds_since(last_estimate_) >= kViewportEstimateSeconds)) {
    const ErrorEstimate e = renderer_.estimate_error();
    estimated_relmse_ = e.known() ? e.relmse : -1;
    last_estimate_ = std::chrono::steady_clock::now();
  }
}

void ViewportRenderer::trace_for_request(const ViewportRequest& request, const Sync& sync,
                                         const std::optional<PixelRect>& region, bool restarted) {
  if (renderer_.sample_count() >= kViewportMaxSamples) return;
  // The budget's pixel-samples are those traced: the region's only.
  const int64_t pixels = region ? int64_t(region->x1 - region->x0) * (region->y1 - region->y0)
                                : int64_t(renderer_.width()) * renderer_.height();
  const bool automatic = request.resolution == ViewportResolution::automatic;
  int k = request.samples_per_frame > 0 ? request.samples_per_frame
          : automatic                   ? preview_.samples(budget_, sync.preview, pixels)
                                        : budget_.samples(pixels);
  k = static_cast<int>(std::min<int64_t>(k, kViewportMaxSamples - renderer_.sample_count()));
  // Busy: no longer than a fluid frame; idle: up to the idle slice (the UI answers in between).
  // A drag restarts every frame, so its pass is traced whole: bands would never finish.
  // An explicit count per frame (tests, the soak) is traced as asked.
  const double slice = request.samples_per_frame > 0 || (request.user_active && restarted) ? 1e30
                       : request.user_active ? budget_.frame_trace_seconds()
                                             : std::max(budget_.frame_trace_seconds(), budget_.config().idle_trace_seconds);
  if (k > 0) trace_slice(k, slice, int64_t(sync.full_w) * sync.full_h);
}

unsigned ViewportRenderer::shown_texture(const Scene& scene, const ViewportRequest& request, FrameStats& stats) {
  // A pass traced in bands is read only once it ends; meanwhile the last image stays.
  const bool mid_pass = renderer_.pass_under_way();
  if (!mid_pass) renderer_.update_display();
  // A preview smaller than the viewport is scaled up smoothly rather than in blocks.
  GLuint tex = renderer_.display_texture();
  if (tex && tex != filtered_texture_) {
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    filtered_texture_ = tex;
  }
  if (request.denoise && !denoiser_) denoiser_ = std::make_unique<ViewportDenoiser>();
  if (denoiser_ && !mid_pass) last_denoised_ = denoiser_->update(renderer_, scene.display, request.denoise);
  if (denoiser_) {
    if (request.denoise && last_denoised_) tex = last_denoised_;
    stats.denoise_status = denoiser_->status();
  }
  // A new level's first pass, traced in bands: the previous level's image until it ends.
  if (renderer_.sample_count() == 0 && held_.texture()) return held_.texture();
  if (renderer_.sample_count() > 0) held_.release();
  return tex;
}

ViewportFrame ViewportRenderer::render(const Scene& scene, const ViewportRequest& request) {
  ViewportFrame out;
  FrameStats& stats = out.stats;
  record_frame_time();
  if (gl_renderer_.empty()) gl_renderer_ = gl_renderer_name();

  const Sync sync = sync_scene(scene, request, stats);
  update_estimate(sync.synced, stats.restarted);
  const bool targeted = request.target_error > 0;
  stats.target_reached = targeted && sync.synced && renderer_.sample_count() >= kErrorTargetMinSamples &&
                         estimated_relmse_ >= 0 && estimated_relmse_ <= request.target_error;
  const std::optional<PixelRect> region =
      request.region ? region_pixels(*request.region, renderer_.width(), renderer_.height()) : std::nullopt;
  renderer_.set_sample_region(region);
  if (request.trace && sync.synced && !stats.target_reached) trace_for_request(request, sync, region, stats.restarted);
  rate_.update(seconds_since(start_));  // samples per pixel per second (editor/sample_rate.h)

  out.display_texture = shown_texture(scene, request, stats);
  if (request.error_map && sync.synced) out.error_map_texture = renderer_.error_map();
  stats.spp = renderer_.sample_count();
  stats.estimated_relmse = estimated_relmse_;
  stats.spp_per_second = rate_.per_second;
  stats.ms_per_frame = ms_per_frame_;
  stats.trace_width = renderer_.width();
  stats.trace_height = renderer_.height();
  stats.divisor = sync.divisor;
  stats.pass_progress = renderer_.pass_under_way()
                            ? 1.0f - float(renderer_.pass_rows_left()) / float(std::max(1, renderer_.height()))
                            : 0.0f;
  stats.gl_renderer = gl_renderer_;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return out;
}

void ViewportRenderer::trace_slice(int samples, double slice_seconds, int64_t full_pixels) {
  const int width = renderer_.width();
  const int64_t pixels = int64_t(width) * renderer_.height();
  auto t0 = std::chrono::steady_clock::now();
  if (!renderer_.pass_under_way()) {
    // A pass that fits the slice goes in one call; a longer one (a fine level, a heavy scene,
    // Preview > full on a slow device) in bands of rows over the next frames.
    if (!(budget_.cost() > 0) || budget_.pass_seconds(pixels) * samples <= slice_seconds ||
        pixels < kMinBandedPixels) {
      renderer_.trace(samples);
      glFinish();  // the budget needs the pass's real time
      const double seconds = seconds_since(t0);
      last_trace_seconds_ += seconds;
      budget_.record(samples, pixels, seconds, full_pixels);
      rate_.add(samples);
      return;
    }
    renderer_.begin_pass(1);
    pass_seconds_ = 0;
  }
  const int pass_samples = renderer_.pass_samples();
  const double row_seconds = budget_.pass_seconds(width) * pass_samples;
  const int rows = int(std::clamp(std::floor(slice_seconds / std::max(row_seconds, 1e-9)), 1.0,
                                  double(std::max(1, renderer_.pass_rows_left()))));
  const int traced = renderer_.trace_rows(rows);
  glFinish();
  const double seconds = seconds_since(t0);
  last_trace_seconds_ += seconds;
  pass_seconds_ += seconds;
  if (traced > 0 && !renderer_.pass_under_way()) {
    // The pass as a whole: each band's own fixed cost (draw set-up, the wait) is part of it,
    // and a band's few rows alone would overstate the cost per sample many times over.
    budget_.record(pass_samples, pixels, pass_seconds_, full_pixels);
    rate_.add(pass_samples);
  }
}

}  // namespace glint
