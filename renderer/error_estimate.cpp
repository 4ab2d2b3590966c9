#include "renderer/error_estimate.h"

#include <stdexcept>

#include "renderer/gl_program.h"

namespace glint {
namespace {

constexpr int kBlock = 16;      // pixels a sum covers per side, per pass
constexpr int kReadBack = 32;   // the sums are read back once neither side exceeds this

int blocks(int n) { return (n + kBlock - 1) / kBlock; }

}  // namespace

ErrorEstimator::ErrorEstimator()
    : program_(std::make_unique<GlProgram>("fullscreen.vert", "error_reduce.frag")) {
  glCreateVertexArrays(1, &vao_);
  // One estimate of a 1x1 image now: a driver that compiles at the first draw (llvmpipe) does
  // it here, when the renderer is made, not during a render (where the soak would count it).
  GLuint pixel = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &pixel);
  glTextureStorage2D(pixel, 1, GL_RGBA32F, 1, 1);
  estimate(pixel, pixel, pixel, 1, 1);
  glDeleteTextures(1, &pixel);
}

ErrorEstimator::~ErrorEstimator() {
  release();
  glDeleteVertexArrays(1, &vao_);
}

void ErrorEstimator::release() {
  for (Level& l : levels_) {
    glDeleteFramebuffers(1, &l.fbo);
    glDeleteTextures(1, &l.texture);
  }
  levels_.clear();
  width_ = height_ = 0;
}

void ErrorEstimator::resize(int width, int height) {
  release();
  width_ = width;
  height_ = height;
  int w = width, h = height;
  do {
    Level l;
    l.width = blocks(w);
    l.height = blocks(h);
    glCreateTextures(GL_TEXTURE_2D, 1, &l.texture);
    glTextureStorage2D(l.texture, 1, GL_RGBA32F, l.width, l.height);
    glTextureParameteri(l.texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(l.texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glCreateFramebuffers(1, &l.fbo);
    glNamedFramebufferTexture(l.fbo, GL_COLOR_ATTACHMENT0, l.texture, 0);
    if (glCheckNamedFramebufferStatus(l.fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("incomplete framebuffer for the error estimate");
    levels_.push_back(l);
    w = l.width;
    h = l.height;
  } while (w > kReadBack || h > kReadBack);
}

ErrorEstimate ErrorEstimator::estimate(GLuint accumulation, GLuint compensation, GLuint variance,
                                       int width, int height) {
  ErrorEstimate e;
  if (width <= 0 || height <= 0) return e;
  if (width != width_ || height != height_) resize(width, height);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_SCISSOR_TEST);
  glUseProgram(program_->id());
  program_->set("u_block", kBlock);
  glBindVertexArray(vao_);
  for (size_t i = 0; i < levels_.size(); ++i) {
    const bool first = i == 0;
    program_->set("u_first", first ? 1 : 0);
    glBindTextureUnit(0, first ? accumulation : levels_[i - 1].texture);
    glBindTextureUnit(1, compensation);
    glBindTextureUnit(2, variance);
    glBindFramebuffer(GL_FRAMEBUFFER, levels_[i].fbo);
    glViewport(0, 0, levels_[i].width, levels_[i].height);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  const Level& last = levels_.back();
  std::vector<float> sums(static_cast<size_t>(last.width) * last.height * 4);
  glGetTextureImage(last.texture, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(sums.size() * sizeof(float)),
                    sums.data());
  double total[4] = {0, 0, 0, 0};
  for (size_t i = 0; i < sums.size(); ++i) total[i % 4] += sums[i];
  e.pixels = static_cast<int64_t>(total[3] + 0.5);
  if (e.pixels > 0) {
    e.relmse = total[0] / total[3];
    e.relmse_per_sample = total[1] / total[3];
    e.mean_samples = total[2] / total[3];
  }
  return e;
}

}  // namespace glint
