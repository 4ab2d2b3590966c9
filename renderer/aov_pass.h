// The auxiliary images for denoising (docs/DESIGN.md, Denoising): albedo and normal at the
// first surface that is not a perfect specular one (shaders/aov.frag), summed sample by sample
// into RGBA32F targets of their own (rgb the sum, a the count) by additive blending. GpuRenderer
// runs it after each colour draw with the same samples when AOVs are enabled
// (GpuRenderer::set_aovs_enabled), so the colour accumulation itself is untouched.
#pragma once

#include <memory>

#include <epoxy/gl.h>

#include "renderer/image.h"

namespace glint {

class GlProgram;

// Mean albedo (rgb in [0,1]) and mean normal (rgb: world-space, unit length on a flat
// surface, shorter where a pixel sees several; zero where the path escaped) per pixel; alpha 1.
struct AovImages {
  Image albedo;
  Image normal;
};

class AovPass {
 public:
  AovPass();  // compiles fullscreen.vert + aov.frag; throws std::runtime_error with the log
  ~AovPass();
  AovPass(const AovPass&) = delete;
  AovPass& operator=(const AovPass&) = delete;

  void resize(int width, int height);
  void clear();
  // The program to set the trace uniforms on before draw().
  GlProgram& program() { return *program_; }
  // Adds the samples the program's uniforms name (u_samples_before, u_samples_per_pass) to
  // image rows [first_row, first_row + rows), with the scene's buffers and textures already
  // bound.
  void draw(int first_row, int rows);
  AovImages read() const;

 private:
  std::unique_ptr<GlProgram> program_;
  GLuint vao_ = 0;
  GLuint albedo_ = 0, normal_ = 0, fbo_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace glint
