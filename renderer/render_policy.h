// How a render to a target runs on this device (docs/DESIGN.md §2): the trace back end for the
// image, and the size of its passes and of the bands they are traced in. `glint render` takes
// all of it; the editor's export takes the back end for its image (its passes follow the UI's
// frame budget instead, ExportJob::step).
#pragma once

#include <optional>
#include <string>

#include "renderer/backend_choice.h"
#include "renderer/render_session.h"
#include "renderer/trace_backend.h"

namespace glint {

// The threads that Mesa's llvmpipe shades with: one per CPU.
int llvmpipe_thread_count();

// The back end for an image of width x height, given the device's choice (timed at 128x128,
// choose_backend): on llvmpipe (`llvmpipe`, with `threads` threads) an image of fewer 64x64
// tiles than threads takes the compute shader, whose work groups spread over every thread (the
// same image). `reason` says why when the back end is not the device's choice, else "".
struct BackendForImage {
  TraceBackend backend = TraceBackend::fragment;
  std::string reason;
};
BackendForImage backend_for_image(TraceBackend device_choice, int width, int height, bool llvmpipe, int threads);

// The passes of a render to `target` that runs to its end (no UI between its steps), and the
// slice of each step (RenderSession::run), after which its progress is shown.
// Passes of many samples, traced in bands of rows: a pass's draws trace up to the loop budget's
// samples per pixel, and in a draw of few samples the lanes whose paths end early wait for the
// longest path of their SIMD group (path regeneration refills them only with the pixel's
// further samples). So: a first pass of about kFirstPassPixelSamples samples in all (tens of
// milliseconds on llvmpipe), then passes grown by rate to about kPassSeconds, each traced in
// bands of about kBandSeconds (whole rows of llvmpipe tiles, band_rows_for_threads) so that
// progress is shown while a pass runs; untiled where the image holds a single band, with
// passes of about kUntiledPassSeconds. Not for a time target, which is checked between passes
// only, nor adaptive sampling, whose threshold is refreshed between passes
// (GpuRenderer::begin_pass): there passes start at one sample and double while under a quarter
// of a second, untiled, one per step.
inline constexpr int64_t kFirstPassPixelSamples = 1 << 17;
inline constexpr double kPassSeconds = 4.0;
inline constexpr double kUntiledPassSeconds = 1.0;
inline constexpr double kBandSeconds = 0.25;
struct SessionPlan {
  RenderSessionOptions options;
  double step_seconds = 0;
};
SessionPlan batch_session_plan(const RenderTarget& target, bool adaptive, bool checkpoints, int width, int height,
                               int threads);

// What a batch render (`glint render`) asks for.
struct BatchRenderRequest {
  int width = 0;
  int height = 0;
  RenderTarget target;
  bool adaptive = false;                // RenderOptions::adaptive
  bool checkpoints = false;             // every power of two hit exactly (a convergence log)
  std::optional<TraceBackend> backend;  // forced; nullopt: the device's choice for the image
};

struct RenderPolicy {
  TraceBackend backend = TraceBackend::fragment;
  std::optional<BackendChoice> device_choice;  // the automatic choice; nullopt when forced
  std::string backend_reason;                  // BackendForImage::reason
  SessionPlan session;
};

// The policy for `request` on the current context's device (needs a current GL 4.5 context:
// the automatic choice may time both back ends, choose_backend).
RenderPolicy batch_render_policy(const BatchRenderRequest& request);

}  // namespace glint
