#include "renderer/render_policy.h"

#include <algorithm>
#include <thread>

#include "renderer/gl_context.h"

namespace glint {

int llvmpipe_thread_count() { return static_cast<int>(std::thread::hardware_concurrency()); }

BackendForImage backend_for_image(TraceBackend device_choice, int width, int height, bool llvmpipe, int threads) {
  if (device_choice == TraceBackend::fragment && llvmpipe && fewer_llvmpipe_tiles_than_threads(width, height, threads))
    return {TraceBackend::compute,
            "compute for an image of fewer 64x64 llvmpipe tiles than its " + std::to_string(threads) + " threads"};
  return {device_choice, ""};
}

SessionPlan batch_session_plan(const RenderTarget& target, bool adaptive, bool checkpoints, int width, int height,
                               int threads) {
  SessionPlan plan;
  plan.options.target = target;
  plan.options.checkpoints = checkpoints;
  if (target.seconds > 0 || adaptive) return plan;
  plan.options.band_rows = band_rows_for_threads(width, threads);
  plan.options.tiled = plan.options.band_rows < height;
  plan.options.batch.grow_by_rate = true;
  plan.options.batch.grow_below = plan.options.tiled ? kPassSeconds : kUntiledPassSeconds;
  plan.options.batch.first_batch =
      static_cast<int>(std::clamp<int64_t>(kFirstPassPixelSamples / (int64_t(width) * height), 1, 16));
  plan.step_seconds = kBandSeconds;
  return plan;
}

RenderPolicy batch_render_policy(const BatchRenderRequest& request) {
  const int threads = llvmpipe_thread_count();
  RenderPolicy policy;
  if (request.backend) {
    policy.backend = *request.backend;
  } else {
    policy.device_choice = choose_backend();
    const BackendForImage b =
        backend_for_image(policy.device_choice->backend, request.width, request.height, on_llvmpipe(), threads);
    policy.backend = b.backend;
    policy.backend_reason = b.reason;
  }
  policy.session = batch_session_plan(request.target, request.adaptive, request.checkpoints, request.width,
                                      request.height, threads);
  return policy;
}

}  // namespace glint
