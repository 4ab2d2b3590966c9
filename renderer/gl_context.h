// A headless OpenGL 4.5 core context through EGL: the EGL device platform first (GPU drivers,
// Mesa's software device), then Mesa's surfaceless platform. Used by `glint render`, the tests
// and the benchmarks; the editor uses its GLFW window's context instead.
#pragma once

#include <memory>
#include <string>

namespace glint {

class HeadlessGLContext {
 public:
  // Creates the context and makes it current on this thread. Throws std::runtime_error with
  // every attempt's reason when no platform gives an OpenGL 4.5 core context.
  static std::unique_ptr<HeadlessGLContext> create();
  ~HeadlessGLContext();
  HeadlessGLContext(const HeadlessGLContext&) = delete;
  HeadlessGLContext& operator=(const HeadlessGLContext&) = delete;

  const std::string& platform() const { return platform_; }  // "EGL device" or "surfaceless"

 private:
  HeadlessGLContext() = default;
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string platform_;
};

// GL_RENDERER and GL_VERSION of the current context, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
std::string gl_renderer_name();
std::string gl_version_string();

}  // namespace glint
