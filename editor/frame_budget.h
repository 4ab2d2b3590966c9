// How much to trace per UI frame: samples per pixel (k) and a viewport resolution divisor.
//
// A trace pass cannot be interrupted, so on a slow device (llvmpipe renders ~0.35 M samples/s)
// even one sample per pixel at full resolution would freeze the UI for seconds. The controller
// therefore learns the cost of one pixel-sample from measured passes and picks the largest
// resolution (smallest divisor) at which one sample fits the trace budget, then as many samples
// as fit. The divisor changes only with hysteresis, because a new size restarts accumulation.
// Pure logic: no GL, no clock; the caller measures.
#pragma once

#include <cstdint>

namespace glint {

struct FrameBudgetConfig {
  double frame_seconds = 0.025;  // whole UI frame target (40 fps, a margin above 30)
  double min_trace_seconds = 0.003;
  double trace_seconds = 0.015;  // per UI frame; adapted by record_frame to what the UI leaves
  int max_samples = 64;          // per frame, so that edits still feel immediate
  int max_divisor = 16;          // never coarser than 1/16 of the framebuffer per axis
  int min_divisor = 1;           // 1: full framebuffer resolution allowed
  // Where the frame target would leave the preview coarser than 1/drag_max_divisor (a slow
  // device, a heavy scene), a drag may take frames of up to drag_frame_seconds instead (about
  // 11 fps): a readable quarter-resolution image is worth more than fluid blocks.
  // The drag's tracing keeps at least drag_min_trace_seconds even where the UI alone takes
  // most of drag_frame_seconds (a loaded machine): the resolution matters more then.
  int drag_max_divisor = 4;
  double drag_frame_seconds = 0.09;
  double drag_min_trace_seconds = 0.04;
  // The automatic preview's idle refinement (PreviewResolution below).
  double idle_delay_seconds = 0.3;  // no edit and no input for this long: refine one step
  // An idle frame traces at most this long, so that the UI answers within about 0.1 s; a pass
  // that takes longer is traced in bands of rows over several frames (ViewportRenderer).
  double idle_trace_seconds = 0.06;
  // Idle refinement goes to a finer level while one pass there takes at most this long (in
  // bands): full resolution on all but the largest windows of the slowest devices.
  double refine_max_pass_seconds = 4.0;
  int refine_min_samples = 4;       // samples per pixel a level shows before the next step
};

class FrameBudget {
 public:
  explicit FrameBudget(FrameBudgetConfig config = {}) : config_(config) {}

  const FrameBudgetConfig& config() const { return config_; }
  void set_config(const FrameBudgetConfig& config);

  // The resolution divisor for a framebuffer of this many pixels (1 = full resolution).
  int divisor() const { return divisor_; }
  // Samples per pixel to trace this frame at `pixels` trace pixels (>= 1), within
  // frame_trace_seconds().
  int samples(int64_t pixels) const;
  // Seconds of tracing a frame at divisor() may take: config().trace_seconds, or the drag's
  // longer frame where the divisor needed it (drag_max_divisor).
  double frame_trace_seconds() const { return trace_budget(divisor_); }

  // Records a finished pass: `samples` per pixel over `pixels` pixels took `seconds`.
  // `full_pixels` is the framebuffer's pixel count (the divisor is chosen against it).
  void record(int samples, int64_t pixels, double seconds, int64_t full_pixels);

  // Records a whole UI frame and the part of it spent tracing: the trace budget becomes the
  // frame target minus the (smoothed) rest, so slow UI drawing leaves less time to trace.
  void record_frame(double frame_seconds, double trace_seconds);

  // The slice a running export traces per UI frame (the viewport pauses meanwhile): the trace
  // budget, but at least twice the UI's own (smoothed) time per frame and at most
  // kMaxExportSliceSeconds. Where drawing the UI is slow (llvmpipe: ~30 ms a frame) the 3 ms
  // floor of the trace budget would leave the export a tenth of the machine; this leaves it two
  // thirds, the UI still answering at about 10 frames a second. Where the UI is quick (a GPU)
  // the trace budget is the larger and the frame target holds.
  static constexpr double kMaxExportSliceSeconds = 0.1;
  double export_slice_seconds() const;

  // Seconds per pixel-sample as currently estimated (0 before the first measurement).
  double cost() const { return cost_; }
  // Estimated seconds of one sample per pixel over `pixels` (0 before the first measurement).
  double pass_seconds(int64_t pixels) const { return cost_ * static_cast<double>(pixels); }

 private:
  int wanted_divisor(int64_t full_pixels) const;
  // The trace seconds a frame at divisor `d` may take (see drag_max_divisor).
  double trace_budget(int d) const;

  FrameBudgetConfig config_;
  double cost_ = 0;
  double overhead_ = -1;
  int divisor_ = 4;      // a cautious start until the first measurement
  int pending_ = 0;      // the divisor the estimates keep asking for
  int pending_frames_ = 0;
};

// What the automatic preview knows about one frame.
struct PreviewFrame {
  bool scene_changed = false;  // this frame's sync restarted the accumulation (an edit, a resize)
  bool user_active = false;    // a widget or viewport drag is held, or the mouse moved or clicked
  double now_seconds = 0;
  int64_t samples = 0;         // samples per pixel accumulated at the current level
  int64_t full_pixels = 1;     // the viewport in framebuffer pixels
};

// The automatic preview's resolution over time (docs/DESIGN.md §2.7). An edit drops it to the
// frame budget's divisor, so that dragging stays fluid; when nothing is edited and the user is
// idle, it refines by halving the divisor down to full resolution, as long as one pass at the
// finer level fits config().refine_max_pass_seconds (traced in bands of at most
// idle_trace_seconds a frame). The level changes only then: frames that edit
// nothing (a click, hovering, exposure and tonemap, which only re-run the tonemap pass) keep
// the level and the accumulation.
class PreviewResolution {
 public:
  // 0 before the first frame.
  int divisor() const { return divisor_; }
  // After a sync at divisor() (or, on the first frame, at any size): the divisor for this
  // frame. A different one than before means the caller re-syncs at it (a restart).
  int update(const FrameBudget& budget, const PreviewFrame& frame);
  // Samples per pixel to trace this frame at the current level (`pixels` trace pixels); 0
  // pauses the accumulation (kept, not restarted) while the user is busy and one pass at this
  // fine level would stall the UI. At a level finer than fluid, at least 1: a pass longer than
  // idle_trace_seconds is then the caller's to trace in bands.
  int samples(const FrameBudget& budget, const PreviewFrame& frame, int64_t pixels) const;

 private:
  int divisor_ = 0;
  double last_change_ = 0;
};

}  // namespace glint
