#include "renderer/gl_context.h"

#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <vector>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include "renderer/egl_device_order.h"

namespace glint {
namespace {

// 4.5 exactly: Mesa refuses 4.6 on llvmpipe.
const EGLint kContextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                  EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};

EGLConfig choose_config(EGLDisplay display) {
  const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (!eglChooseConfig(display, config_attribs, &config, 1, &count) || count == 0) return nullptr;
  return config;
}

// Tries to create and bind a 4.5 core context on `display`; returns the context or null.
EGLContext make_context(EGLDisplay display, std::string& why) {
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) {
    why = "eglInitialize failed";
    return EGL_NO_CONTEXT;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    why = "no desktop OpenGL API";
    eglTerminate(display);
    return EGL_NO_CONTEXT;
  }
  EGLConfig config = choose_config(display);
  if (!config) {
    // Some device displays offer no configs; contexts without one still work there.
    if (!epoxy_has_egl_extension(display, "EGL_KHR_no_config_context")) {
      why = "no OpenGL-renderable EGL config";
      eglTerminate(display);
      return EGL_NO_CONTEXT;
    }
    config = EGL_NO_CONFIG_KHR;
  }
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, kContextAttribs);
  if (context == EGL_NO_CONTEXT) {
    why = "no OpenGL 4.5 core context (EGL error " + std::to_string(eglGetError()) + ")";
    eglTerminate(display);
    return EGL_NO_CONTEXT;
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    why = "cannot make the context current without a surface";
    eglDestroyContext(display, context);
    eglTerminate(display);
    return EGL_NO_CONTEXT;
  }
  return context;
}

// The CUDA device number of an NVIDIA EGL device (EGL_NV_device_cuda), nullopt for others.
std::optional<int> cuda_device_of(EGLDeviceEXT device) {
  const char* extensions = eglQueryDeviceStringEXT(device, EGL_EXTENSIONS);
  if (!extensions || std::string(extensions).find("EGL_NV_device_cuda") == std::string::npos) return std::nullopt;
  EGLAttrib id = -1;
  if (!eglQueryDeviceAttribEXT(device, EGL_CUDA_DEVICE_NV, &id) || id < 0) return std::nullopt;
  return static_cast<int>(id);
}

}  // namespace

std::unique_ptr<HeadlessGLContext> HeadlessGLContext::create() {
  std::string errors;
  std::unique_ptr<HeadlessGLContext> result(new HeadlessGLContext());

  // Makes the context on `display` current and keeps it, or records why it failed.
  auto try_display = [&](EGLDisplay display, const std::string& platform) {
    std::string why = "no display";
    EGLContext context = display == EGL_NO_DISPLAY ? EGL_NO_CONTEXT : make_context(display, why);
    if (context == EGL_NO_CONTEXT) {
      errors += "  " + platform + ": " + why + "\n";
      return false;
    }
    result->display_ = display;
    result->context_ = context;
    result->platform_ = platform;
    return true;
  };

  if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device")) {
    EGLint n = 0;
    eglQueryDevicesEXT(0, nullptr, &n);
    std::vector<EGLDeviceEXT> devices(static_cast<size_t>(n));
    if (n > 0) eglQueryDevicesEXT(n, devices.data(), &n);
    // The GPU a scheduler gave this process first (egl_device_order.h).
    std::vector<std::optional<int>> cuda_ids(devices.size());
    if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_query"))
      for (size_t i = 0; i < devices.size(); ++i) cuda_ids[i] = cuda_device_of(devices[i]);
    const char* visible = std::getenv("CUDA_VISIBLE_DEVICES");
    const EglDeviceOrder order =
        egl_device_order(visible ? std::optional<std::string>(visible) : std::nullopt, cuda_ids);
    for (int i : order.devices)
      if (try_display(eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr),
                      "EGL device " + std::to_string(i) + (order.note.empty() ? "" : " (" + order.note + ")")))
        return result;
    if (n == 0) errors += "  EGL device platform: no devices\n";
  } else {
    errors += "  EGL device platform: not supported\n";
  }

  if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless")) {
    if (try_display(eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                    "surfaceless"))
      return result;
  } else {
    errors += "  Mesa surfaceless platform: not supported\n";
  }
  throw std::runtime_error("cannot create a headless OpenGL 4.5 core context:\n" + errors);
}

std::unique_ptr<HeadlessGLContext> HeadlessGLContext::create_shared() const {
  EGLConfig config = choose_config(display_);
  EGLContext context = eglCreateContext(display_, config ? config : EGL_NO_CONFIG_KHR,
                                        static_cast<EGLContext>(context_), kContextAttribs);
  if (context == EGL_NO_CONTEXT)
    throw std::runtime_error("cannot create a shared OpenGL context (EGL error " +
                             std::to_string(eglGetError()) + ")");
  std::unique_ptr<HeadlessGLContext> shared(new HeadlessGLContext());
  shared->display_ = display_;
  shared->context_ = context;
  shared->owns_display_ = false;
  shared->platform_ = platform_;
  return shared;
}

void HeadlessGLContext::make_current() const {
  if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, static_cast<EGLContext>(context_)))
    throw std::runtime_error("cannot make an OpenGL context current (EGL error " +
                             std::to_string(eglGetError()) + ")");
}

void HeadlessGLContext::release_current() const {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

HeadlessGLContext::~HeadlessGLContext() {
  if (!display_) return;
  if (!owns_display_) {
    // Unbinds it only if it is current on this thread; a context current elsewhere is freed
    // by EGL once released there.
    if (eglGetCurrentContext() == static_cast<EGLContext>(context_)) release_current();
    eglDestroyContext(display_, static_cast<EGLContext>(context_));
    return;
  }
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (context_) eglDestroyContext(display_, context_);
  eglTerminate(display_);
}

std::string gl_renderer_name() {
  const GLubyte* s = glGetString(GL_RENDERER);
  return s ? reinterpret_cast<const char*>(s) : "unknown";
}

bool on_llvmpipe() { return gl_renderer_name().find("llvmpipe") != std::string::npos; }

std::string gl_version_string() {
  const GLubyte* s = glGetString(GL_VERSION);
  return s ? reinterpret_cast<const char*>(s) : "unknown";
}

}  // namespace glint
