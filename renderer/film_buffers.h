// The film of the GPU renderer (docs/DESIGN.md §3.6, Accumulation): the RGBA32F targets a trace
// pass adds its samples to (running mean and its Kahan compensation, variance and its
// compensation; a ping-pong pair of each on the fragment path, one written in place on the
// compute path), and the RGBA8 display image the tonemap pass makes of the mean.
#pragma once

#include <memory>

#include <epoxy/gl.h>

#include "renderer/image.h"
#include "renderer/scene.h"
#include "renderer/trace_backend.h"

namespace glint {

class GlProgram;

// A framebuffer drawing into the four targets of a trace pass (locations 0-3).
GLuint make_trace_framebuffer(const TraceTargets& targets);

class FilmBuffers {
 public:
  // Compiles the tonemap program; throws std::runtime_error with the driver's log. No storage
  // until resize().
  explicit FilmBuffers(TraceBackend backend);
  ~FilmBuffers();
  FilmBuffers(const FilmBuffers&) = delete;
  FilmBuffers& operator=(const FilmBuffers&) = delete;

  // Replaces the storage by width x height (none for an empty film); the targets hold garbage
  // until clear().
  void resize(int width, int height);
  // Zeros every target of both sides and marks the display stale.
  void clear();
  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return width_ <= 0 || height_ <= 0; }

  // Side `side` of the ping-pong pair (0 only on the compute path), and the framebuffer that
  // draws into it (fragment path).
  TraceTargets targets(int side) const {
    return {accumulation_[side], compensation_[side], variance_[side], variance_compensation_[side]};
  }
  GLuint framebuffer(int side) const { return framebuffer_[side]; }
  // The side that holds the latest result (always 0 on the compute path).
  int latest() const { return latest_; }
  void set_latest(int side) { latest_ = side; }

  // The tonemap's exposure and curve; marks the display stale.
  void set_display_settings(const DisplaySettings& display);
  // The latest side changed: the next update_display() runs the tonemap pass again.
  void mark_display_stale() { display_stale_ = true; }
  // Runs the tonemap pass over the latest mean if it is stale (a full-screen triangle drawn
  // with `vao` bound). Never touches the accumulation.
  void update_display(GLuint vao);
  GLuint display_texture() const { return display_texture_; }

  // Read-back of the latest side: the mean (rgb) and discarded count (a); the variance (rgb)
  // and the samples taken (a, from the compensation target); the display image in [0,1] as
  // last drawn (the caller runs update_display first).
  Image read_accumulation() const;
  Image read_variance() const;
  // Coverage (GpuRenderer::read_coverage): the variance's a (covered samples) over the finite
  // samples (compensation's a, taken, less accumulation's a, discarded).
  Image read_coverage() const;
  Image read_display() const;

 private:
  void release();

  TraceBackend backend_;
  std::unique_ptr<GlProgram> tonemap_program_;
  int width_ = 0;
  int height_ = 0;
  int latest_ = 0;
  bool display_stale_ = true;
  GLuint accumulation_[2] = {0, 0};
  GLuint compensation_[2] = {0, 0};  // what each accumulation's float32 mean could not hold
  GLuint variance_[2] = {0, 0};      // mean squared deviation of each pixel's samples
  GLuint variance_compensation_[2] = {0, 0};
  GLuint framebuffer_[2] = {0, 0};  // each draws into the four targets of side i
  GLuint display_texture_ = 0;
  GLuint display_framebuffer_ = 0;
};

}  // namespace glint
