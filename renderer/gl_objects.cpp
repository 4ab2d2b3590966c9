#include "renderer/gl_objects.h"

#include <cstdio>
#include <stdexcept>
#include <vector>

namespace glint {

void clear_gl_errors() {
  while (glGetError() != GL_NO_ERROR) {
  }
}

std::string gl_error_text() {
  const GLenum error = glGetError();
  if (error == GL_NO_ERROR) return "";
  clear_gl_errors();
  if (error == GL_OUT_OF_MEMORY) return "the OpenGL driver is out of memory";
  char text[64];
  std::snprintf(text, sizeof text, "OpenGL error 0x%04x", error);
  return text;
}

GLuint make_texture_2d(GLenum internal_format, int width, int height) {
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, internal_format, width, height);
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

GLuint make_framebuffer(std::initializer_list<GLuint> textures) {
  GLuint fbo = 0;
  glCreateFramebuffers(1, &fbo);
  std::vector<GLenum> attachments;
  for (GLuint t : textures) {
    const GLenum a = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(attachments.size());
    glNamedFramebufferTexture(fbo, a, t, 0);
    attachments.push_back(a);
  }
  glNamedFramebufferDrawBuffers(fbo, static_cast<GLsizei>(attachments.size()), attachments.data());
  if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("incomplete framebuffer for the render target");
  return fbo;
}

}  // namespace glint
