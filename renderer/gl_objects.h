// Small OpenGL helpers of the renderer's units: error text for messages, and the 2-D textures and
// framebuffers the film and the passes draw into.
#pragma once

#include <initializer_list>
#include <string>

#include <epoxy/gl.h>

namespace glint {

// Discards every pending OpenGL error, so that gl_error_text() reports what follows only.
void clear_gl_errors();

// The first OpenGL error since the last call (all are cleared), or "" if none.
std::string gl_error_text();

// A 2-D texture of one level, sampled nearest and clamped at the edges.
GLuint make_texture_2d(GLenum internal_format, int width, int height);

// A framebuffer drawing into `textures` at locations 0, 1, ...; throws std::runtime_error if
// the driver finds it incomplete.
GLuint make_framebuffer(std::initializer_list<GLuint> textures);

}  // namespace glint
