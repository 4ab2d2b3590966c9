#include "editor/held_image.h"

#include <epoxy/gl.h>

namespace glint {

HeldImage::~HeldImage() { release(); }

void HeldImage::release() {
  if (texture_) glDeleteTextures(1, &texture_);
  texture_ = 0;
  width_ = height_ = format_ = 0;
}

void HeldImage::keep(unsigned source) {
  if (!source) return release();
  GLint w = 0, h = 0, format = 0;
  glGetTextureLevelParameteriv(source, 0, GL_TEXTURE_WIDTH, &w);
  glGetTextureLevelParameteriv(source, 0, GL_TEXTURE_HEIGHT, &h);
  glGetTextureLevelParameteriv(source, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
  if (w <= 0 || h <= 0) return release();
  if (w != width_ || h != height_ || format != format_) {
    release();
    glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
    glTextureStorage2D(texture_, 1, GLenum(format), w, h);
    glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    width_ = w;
    height_ = h;
    format_ = format;
  }
  glCopyImageSubData(source, GL_TEXTURE_2D, 0, 0, 0, 0, texture_, GL_TEXTURE_2D, 0, 0, 0, 0, w, h, 1);
}

}  // namespace glint
