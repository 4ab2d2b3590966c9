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

  // A second context on the same display that shares this one's objects (programs, buffers,
  // textures; not framebuffers or vertex arrays), for work on another thread. Not current
  // anywhere; it must be destroyed before this one. Throws std::runtime_error.
  std::unique_ptr<HeadlessGLContext> create_shared() const;
  // Binds this context to the calling thread (or unbinds whatever is bound there); throws
  // std::runtime_error if EGL refuses.
  void make_current() const;
  void release_current() const;

 private:
  HeadlessGLContext() = default;
  void* display_ = nullptr;
  void* context_ = nullptr;
  bool owns_display_ = true;  // a shared context leaves eglTerminate to its parent
  std::string platform_;
};

// GL_RENDERER and GL_VERSION of the current context, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
std::string gl_renderer_name();
std::string gl_version_string();
// The current context is Mesa's llvmpipe (the CPU driver: its tiles, threads and, on Mesa 22,
// its loop limit).
bool on_llvmpipe();

}  // namespace glint
