// The live error map: each pixel's estimated relMSE (the per-pixel term of the image's error
// estimate, renderer/error_estimate.h) drawn as a heat colour on a log scale into an RGBA8
// texture of the film's size (shaders/error_map.frag), which the editor lays over the viewport
// to show where the noise is. Cold (blue) at kErrorMapLow and below, hot (red) at kErrorMapHigh
// and above; pixels without an estimate are transparent.
#pragma once

#include <memory>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

namespace glint {

class GlProgram;

constexpr float kErrorMapLow = 1e-4f;   // relMSE shown coldest
constexpr float kErrorMapHigh = 1.0f;   // ... and hottest
constexpr float kErrorMapOpacity = 0.75f;

// The heat colour of a relMSE (the shader's ramp, for legends and tests): rgb in [0, 1].
glm::vec3 error_map_colour(float relmse);

class ErrorMap {
 public:
  ErrorMap();  // compiles fullscreen.vert + error_map.frag; throws std::runtime_error
  ~ErrorMap();
  ErrorMap(const ErrorMap&) = delete;
  ErrorMap& operator=(const ErrorMap&) = delete;

  // Draws the map of a width x height accumulation (the trace pass's textures) and returns its
  // texture (valid until the next call). Leaves the framebuffer binding at 0.
  GLuint draw(GLuint accumulation, GLuint compensation, GLuint variance, int width, int height);

 private:
  std::unique_ptr<GlProgram> program_;
  GLuint vao_ = 0, texture_ = 0, fbo_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace glint
