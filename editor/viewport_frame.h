// What the viewport renderer is asked for and what it gives back each frame: plain values, so
// that it needs no UI state (docs/DESIGN.md §2.1).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "renderer/render_options.h"
#include "renderer/sample_region.h"

namespace glint {

enum class ViewportResolution { automatic, full, half, quarter };

// One frame's request: the panel's size this frame and how to preview.
struct ViewportRequest {
  int width = 1, height = 1;  // the panel in framebuffer pixels (HiDPI: more than its points)
  ViewportResolution resolution = ViewportResolution::automatic;  // automatic: the frame budget
  RenderOptions estimator;  // how the viewport samples (not saved in the project)
  bool trace = true;        // false while an export has the device: sync and tonemap only
  int samples_per_frame = 0;  // > 0: trace exactly this many, not the frame budget's (repeatable runs)
  // > 0: accumulation pauses once the estimated relMSE (GpuRenderer::estimate_error) is at most
  // this, from kErrorTargetMinSamples on (renderer/render_session.h).
  double target_error = 0;
  bool denoise = false;     // show the denoised image (editor/viewport_denoiser.h; biased)
  // > 0: the export's film; the viewport camera frames it (editor/film_frame.h).
  int film_width = 0, film_height = 0;
  // The user holds a widget or a viewport drag, or moved or clicked the mouse this frame: the
  // automatic preview does not refine then (editor/frame_budget.h).
  bool user_active = false;
  // Region render: only these pixels (fractions of the image) take samples (GpuRenderer::
  // set_sample_region); nullopt: all.
  std::optional<FractionRect> region;
  bool error_map = false;  // draw the error map (ViewportFrame::error_map_texture)
};

struct FrameStats {
  int64_t spp = 0;
  double spp_per_second = 0;
  double ms_per_frame = 0;
  int trace_width = 0, trace_height = 0;
  int divisor = 1;         // the viewport's framebuffer pixels per trace pixel, per axis
  float pass_progress = 0; // a pass traced in bands: the fraction of its rows done (0: none)
  bool restarted = false;  // this frame's sync reset the accumulation
  double estimated_relmse = -1;  // the image's estimated relMSE; -1 while unknown
  bool target_reached = false;   // paused at the request's target_error
  std::string gl_renderer;
  std::string scene_problem;  // why the viewport is not updating (an invalid value), or ""
  std::string denoise_status;  // with ViewportRequest::denoise: what is shown, or why not
};

// The frame's result: the image to show for the requested size (0 before the first one) and
// the figures of the status bar.
struct ViewportFrame {
  unsigned display_texture = 0;
  unsigned error_map_texture = 0;  // with ViewportRequest::error_map (renderer/error_map.h)
  FrameStats stats;
};

}  // namespace glint
