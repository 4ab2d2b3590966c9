#include "renderer/film_buffers.h"

#include <algorithm>
#include <vector>

#include "renderer/gl_objects.h"
#include "renderer/gl_program.h"

namespace glint {
namespace {

// An RGBA image of width x height read from `texture` as floats.
Image read_rgba(GLuint texture, int width, int height) {
  Image image = Image::filled(width, height, 0.0f);
  glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT,
                    static_cast<GLsizei>(image.pixels.size() * sizeof(float)), image.pixels.data());
  return image;
}

}  // namespace

GLuint make_trace_framebuffer(const TraceTargets& t) {
  return make_framebuffer({t.accumulation, t.compensation, t.variance, t.variance_compensation});
}

FilmBuffers::FilmBuffers(TraceBackend backend)
    : backend_(backend), tonemap_program_(std::make_unique<GlProgram>("fullscreen.vert", "tonemap.frag")) {}

FilmBuffers::~FilmBuffers() { release(); }

void FilmBuffers::release() {
  if (!accumulation_[0]) return;
  glDeleteFramebuffers(2, framebuffer_);  // names of 0 are ignored
  glDeleteTextures(2, accumulation_);
  glDeleteTextures(2, compensation_);
  glDeleteTextures(2, variance_);
  glDeleteTextures(2, variance_compensation_);
  glDeleteFramebuffers(1, &display_framebuffer_);
  glDeleteTextures(1, &display_texture_);
  for (int i = 0; i < 2; ++i)
    accumulation_[i] = compensation_[i] = variance_[i] = variance_compensation_[i] = framebuffer_[i] = 0;
  display_texture_ = display_framebuffer_ = 0;
}

void FilmBuffers::resize(int width, int height) {
  release();
  width_ = width;
  height_ = height;
  if (empty()) return;
  const bool compute = backend_ == TraceBackend::compute;
  for (int i = 0; i < (compute ? 1 : 2); ++i) {
    accumulation_[i] = make_texture_2d(GL_RGBA32F, width, height);
    compensation_[i] = make_texture_2d(GL_RGBA32F, width, height);
    variance_[i] = make_texture_2d(GL_RGBA32F, width, height);
    variance_compensation_[i] = make_texture_2d(GL_RGBA32F, width, height);
    if (!compute) framebuffer_[i] = make_trace_framebuffer(targets(i));
  }
  display_texture_ = make_texture_2d(GL_RGBA8, width, height);
  // Shown scaled when the editor previews at reduced resolution: smooth, not blocky.
  glTextureParameteri(display_texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  display_framebuffer_ = make_framebuffer({display_texture_});
}

void FilmBuffers::clear() {
  const float zero[4] = {0, 0, 0, 0};
  for (int i = 0; i < 2; ++i)
    for (GLuint t : {accumulation_[i], compensation_[i], variance_[i], variance_compensation_[i]})
      if (t) glClearTexImage(t, 0, GL_RGBA, GL_FLOAT, zero);
  display_stale_ = true;
}

void FilmBuffers::set_display_settings(const DisplaySettings& display) {
  tonemap_program_->set("u_exposure", display.exposure);
  tonemap_program_->set("u_tonemap", display.tonemap == Tonemap::filmic ? 0 : 1);
  display_stale_ = true;
}

void FilmBuffers::update_display(GLuint vao) {
  if (!display_stale_ || width_ <= 0) return;
  glBindFramebuffer(GL_FRAMEBUFFER, display_framebuffer_);
  glViewport(0, 0, width_, height_);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_SCISSOR_TEST);
  glUseProgram(tonemap_program_->id());
  glBindTextureUnit(0, accumulation_[latest_]);
  glBindVertexArray(vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  display_stale_ = false;
}

Image FilmBuffers::read_accumulation() const { return read_rgba(accumulation_[latest_], width_, height_); }

Image FilmBuffers::read_variance() const {
  Image image = read_rgba(variance_[latest_], width_, height_);
  const Image samples = read_rgba(compensation_[latest_], width_, height_);
  for (size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = samples.pixels[i];
  return image;
}

Image FilmBuffers::read_coverage() const {
  Image image = read_rgba(variance_[latest_], width_, height_);
  const Image taken = read_rgba(compensation_[latest_], width_, height_);
  const Image discarded = read_rgba(accumulation_[latest_], width_, height_);
  for (size_t i = 0; i < image.pixels.size(); i += 4) {
    const float finite = taken.pixels[i + 3] - discarded.pixels[i + 3];
    const float coverage = finite > 0 ? std::clamp(image.pixels[i + 3] / finite, 0.0f, 1.0f) : 0.0f;
    for (int c = 0; c < 4; ++c) image.pixels[i + c] = coverage;
  }
  return image;
}

Image FilmBuffers::read_display() const { return read_rgba(display_texture_, width_, height_); }

}  // namespace glint
