#include "editor/frame_budget.h"

#include <algorithm>
#include <cmath>

namespace glint {

void FrameBudget::set_config(const FrameBudgetConfig& config) {
  config_ = config;
  divisor_ = std::clamp(divisor_, config_.min_divisor, config_.max_divisor);
}

void FrameBudget::record_frame(double frame_seconds, double trace_seconds) {
  if (!(frame_seconds > 0) || !(trace_seconds >= 0)) return;
  double rest = std::max(0.0, frame_seconds - trace_seconds);
  overhead_ = overhead_ < 0 ? rest : 0.9 * overhead_ + 0.1 * rest;
  config_.trace_seconds = std::max(config_.min_trace_seconds, config_.frame_seconds - overhead_);
}

double FrameBudget::export_slice_seconds() const {
  const double ui = overhead_ > 0 ? overhead_ : 0.0;
  return std::min(kMaxExportSliceSeconds, std::max(config_.trace_seconds, 2 * ui));
}

double FrameBudget::trace_budget(int d) const {
  if (d < config_.drag_max_divisor) return config_.trace_seconds;
  const double ui = overhead_ > 0 ? overhead_ : 0.0;
  return std::max({config_.trace_seconds, config_.drag_frame_seconds - ui, config_.drag_min_trace_seconds});
}

int FrameBudget::samples(int64_t pixels) const {
  if (cost_ <= 0 || pixels <= 0) return 1;
  double k = frame_trace_seconds() / (cost_ * static_cast<double>(pixels));
  return static_cast<int>(std::clamp(std::floor(k), 1.0, static_cast<double>(config_.max_samples)));
}

int FrameBudget::wanted_divisor(int64_t full_pixels) const {
  // Smallest d with full_pixels / d^2 * cost <= trace_budget(d): one sample per pixel fits.
  for (int d = config_.min_divisor; d < config_.max_divisor; ++d)
    if (cost_ * static_cast<double>(full_pixels) / (double(d) * d) <= trace_budget(d)) return d;
  return std::max(config_.min_divisor, config_.max_divisor);
}

void FrameBudget::record(int samples, int64_t pixels, double seconds, int64_t full_pixels) {
  if (samples <= 0 || pixels <= 0 || !(seconds > 0)) return;
  double measured = seconds / (static_cast<double>(samples) * static_cast<double>(pixels));
  // Smooth, but follow large increases at once so that a heavy scene never stalls the UI.
  cost_ = cost_ <= 0 || measured > 2 * cost_ ? measured : 0.8 * cost_ + 0.2 * measured;

  int want = wanted_divisor(full_pixels);
  if (want > divisor_) {
    divisor_ = want;  // too slow: coarser at once
    pending_frames_ = 0;
    return;
  }
  // Finer only when the finer size fits with 30% headroom for several frames in a row.
  if (want < divisor_) {
    double fine_seconds = cost_ * static_cast<double>(full_pixels) / (double(want) * want);
    if (fine_seconds * 1.3 > trace_budget(want)) want += 1;
    if (want < divisor_) {
      pending_frames_ = want == pending_ ? pending_frames_ + 1 : 1;
      pending_ = want;
      if (pending_frames_ >= 10) {
        divisor_ = want;
        pending_frames_ = 0;
      }
      return;
    }
  }
  pending_frames_ = 0;
}

int PreviewResolution::update(const FrameBudget& budget, const PreviewFrame& f) {
  const FrameBudgetConfig& c = budget.config();
  if (divisor_ == 0 || f.scene_changed) {
    divisor_ = budget.divisor();  // fluid while editing
    last_change_ = f.now_seconds;
    return divisor_;
  }
  // A level too slow even for an idle frame (the first frame's guess on a slow device, or a
  // scene that became heavier without an edit, such as a new shader variant): back to fluid.
  // 1.5x above what refinement accepts, so that the two never alternate.
  const int64_t level_pixels = f.full_pixels / (int64_t(divisor_) * divisor_);
  if (divisor_ < budget.divisor() && budget.pass_seconds(level_pixels) > 1.5 * c.refine_max_pass_seconds) {
    divisor_ = budget.divisor();
    last_change_ = f.now_seconds;
    return divisor_;
  }
  const bool settled = !f.user_active && f.now_seconds - last_change_ >= c.idle_delay_seconds &&
                       f.samples >= c.refine_min_samples;
  if (settled && divisor_ > c.min_divisor && budget.cost() > 0) {
    const int finer = std::max(c.min_divisor, divisor_ / 2);
    const int64_t finer_pixels = f.full_pixels / (int64_t(finer) * finer);
    if (budget.pass_seconds(finer_pixels) <= c.refine_max_pass_seconds) {
      divisor_ = finer;
      last_change_ = f.now_seconds;
    }
  }
  return divisor_;
}

int PreviewResolution::samples(const FrameBudget& budget, const PreviewFrame& f, int64_t pixels) const {
  const FrameBudgetConfig& c = budget.config();
  const double pass = budget.pass_seconds(pixels);
  // At the fluid level (or when a pass fits a fluid frame anyway): the frame budget.
  if (divisor_ >= budget.divisor() || pass <= budget.frame_trace_seconds()) return budget.samples(pixels);
  if (f.user_active) return 0;  // a finer level than fluid: wait for the user
  double k = c.idle_trace_seconds / std::max(pass, 1e-12);
  return static_cast<int>(std::clamp(std::floor(k), 1.0, static_cast<double>(c.max_samples)));
}

}  // namespace glint
