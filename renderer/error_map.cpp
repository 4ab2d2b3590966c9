#include "renderer/error_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "renderer/gl_program.h"

namespace glint {

glm::vec3 error_map_colour(float relmse) {
  static const glm::vec3 stops[5] = {{0.1f, 0.2f, 1.0f}, {0.0f, 0.9f, 1.0f}, {0.1f, 0.9f, 0.2f},
                                     {1.0f, 0.9f, 0.0f}, {1.0f, 0.1f, 0.05f}};
  const float low = std::log10(kErrorMapLow), high = std::log10(kErrorMapHigh);
  const float t = (std::log10(std::max(relmse, 1e-30f)) - low) / (high - low);
  const float x = std::clamp(t, 0.0f, 1.0f) * 4;
  const int i = std::min(static_cast<int>(x), 3);
  return glm::mix(stops[i], stops[i + 1], x - static_cast<float>(i));
}

ErrorMap::ErrorMap() : program_(std::make_unique<GlProgram>("fullscreen.vert", "error_map.frag")) {
  glCreateVertexArrays(1, &vao_);
}

ErrorMap::~ErrorMap() {
  glDeleteFramebuffers(1, &fbo_);
  glDeleteTextures(1, &texture_);
  glDeleteVertexArrays(1, &vao_);
}

GLuint ErrorMap::draw(GLuint accumulation, GLuint compensation, GLuint variance, int width, int height) {
  if (width <= 0 || height <= 0) return 0;
  if (width != width_ || height != height_) {
    glDeleteFramebuffers(1, &fbo_);
    glDeleteTextures(1, &texture_);
    glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
    glTextureStorage2D(texture_, 1, GL_RGBA8, width, height);
    glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glCreateFramebuffers(1, &fbo_);
    glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, texture_, 0);
    if (glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("incomplete framebuffer for the error map");
    width_ = width;
    height_ = height;
  }
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_SCISSOR_TEST);
  glUseProgram(program_->id());
  program_->set("u_log_low", std::log10(kErrorMapLow));
  program_->set("u_log_high", std::log10(kErrorMapHigh));
  program_->set("u_opacity", kErrorMapOpacity);
  glBindTextureUnit(0, accumulation);
  glBindTextureUnit(1, compensation);
  glBindTextureUnit(2, variance);
  glBindVertexArray(vao_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width, height);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return texture_;
}

}  // namespace glint
