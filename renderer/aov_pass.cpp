#include "renderer/aov_pass.h"

#include <stdexcept>

#include "renderer/gl_program.h"

namespace glint {

AovPass::AovPass() : program_(std::make_unique<GlProgram>("fullscreen.vert", "aov.frag")) {
  glCreateVertexArrays(1, &vao_);
}

AovPass::~AovPass() {
  resize(0, 0);
  glDeleteVertexArrays(1, &vao_);
}

void AovPass::resize(int width, int height) {
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  if (albedo_) glDeleteTextures(1, &albedo_);
  if (normal_) glDeleteTextures(1, &normal_);
  fbo_ = albedo_ = normal_ = 0;
  width_ = width;
  height_ = height;
  if (width <= 0 || height <= 0) return;
  for (GLuint* t : {&albedo_, &normal_}) {
    glCreateTextures(GL_TEXTURE_2D, 1, t);
    glTextureStorage2D(*t, 1, GL_RGBA32F, width, height);
  }
  glCreateFramebuffers(1, &fbo_);
  glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, albedo_, 0);
  glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT1, normal_, 0);
  const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(fbo_, 2, both);
  if (glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("incomplete framebuffer for the auxiliary images");
  clear();
  // A pass of no samples (it adds 0), with the blending of a real one: a driver that compiles
  // at the first draw for the pipeline state (Mesa's llvmpipe JITs then, blending included, a
  // second or more) does it here, not inside the first timed trace pass.
  program_->set("u_samples_per_pass", 0);
  draw(0, height_);
  glFinish();
}

void AovPass::clear() {
  const float zero[4] = {0, 0, 0, 0};
  for (GLuint t : {albedo_, normal_})
    if (t) glClearTexImage(t, 0, GL_RGBA, GL_FLOAT, zero);
}

void AovPass::draw(int first_row, int rows) {
  if (!fbo_) return;
  program_->set("u_resolution", glm::ivec2(width_, height_));
  glUseProgram(program_->id());
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width_, height_);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, first_row, width_, rows);  // window row y is texel row y
  glEnable(GL_BLEND);  // float32 targets blend unclamped: a running sum
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

AovImages AovPass::read() const {
  AovImages out;
  for (Image* image : {&out.albedo, &out.normal}) {
    image->width = width_;
    image->height = height_;
    image->pixels.assign(static_cast<size_t>(width_) * height_ * 4, 0.0f);
  }
  if (!fbo_) return out;
  glGetTextureImage(albedo_, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(out.albedo.pixels.size() * 4),
                    out.albedo.pixels.data());
  glGetTextureImage(normal_, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(out.normal.pixels.size() * 4),
                    out.normal.pixels.data());
  for (Image* image : {&out.albedo, &out.normal})
    for (size_t i = 0; i < image->pixels.size(); i += 4) {
      const float count = image->pixels[i + 3];
      for (int c = 0; c < 3; ++c) image->pixels[i + c] = count > 0 ? image->pixels[i + c] / count : 0.0f;
      image->pixels[i + 3] = 1.0f;
    }
  return out;
}

}  // namespace glint
