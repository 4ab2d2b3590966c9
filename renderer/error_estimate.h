// The image's error estimated without a reference (docs/DESIGN.md §4.1): from the per-pixel
// variance that the trace pass keeps beside the mean (shaders/trace_common.glsl), the relMSE
// of renderer/image_metrics.h (epsilon 0.01) that the image is expected to have against the
// converged one. Computed on the GPU by shaders/error_reduce.frag, which sums 16x16 blocks
// until at most 32x32 sums are left; only those are read back (16 KiB at most), so asking for
// it every pass costs a few small draws and one small read-back, not the image.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <epoxy/gl.h>

namespace glint {

class GlProgram;

struct ErrorEstimate {
  // Pixels with an estimate (at least two finite samples); 0: nothing is known yet.
  int64_t pixels = 0;
  // Mean over those pixels of their estimated relMSE: the estimated relMSE of the image.
  double relmse = 0;
  // Mean over them of relMSE / n, the error per finite sample: adaptive sampling's threshold.
  double relmse_per_sample = 0;
  // Mean finite samples per pixel (below the pass count with adaptive sampling).
  double mean_samples = 0;
  bool known() const { return pixels > 0; }
};

class ErrorEstimator {
 public:
  ErrorEstimator();
  ~ErrorEstimator();
  ErrorEstimator(const ErrorEstimator&) = delete;
  ErrorEstimator& operator=(const ErrorEstimator&) = delete;

  // The estimate of a width x height accumulation (the trace pass's textures). Leaves the
  // framebuffer binding at 0; waits for the GPU (the read-back of the sums).
  ErrorEstimate estimate(GLuint accumulation, GLuint compensation, GLuint variance, int width,
                         int height);

 private:
  struct Level {
    GLuint texture = 0;
    GLuint fbo = 0;
    int width = 0;
    int height = 0;
  };
  void resize(int width, int height);
  void release();

  std::unique_ptr<GlProgram> program_;
  GLuint vao_ = 0;
  std::vector<Level> levels_;  // the sums of each pass, first pass first
  int width_ = 0;
  int height_ = 0;
};

}  // namespace glint
