// Compiles programs on a second thread, in an OpenGL context that shares objects with the
// renderer's, and draws one pixel with each there.
//
// Why: Mesa's llvmpipe links synchronously inside glLinkProgram (45-55 ms for a trace variant)
// although it advertises GL_KHR_parallel_shader_compile, and it JIT-compiles the shader at the
// first draw that uses it (0.6-1.0 s cold). Either, on the editor's thread, freezes the UI after
// a structural edit. Done here, the link and the first-draw compile happen off the UI thread;
// llvmpipe keeps the compiled code in its shader cache, so the renderer's own first draw with
// the program then takes milliseconds (gl.GlProgramWorker.*; figures in the README).
//
// The renderer knows nothing of windows: whoever owns the contexts (the editor's GLFW windows,
// or HeadlessGLContext::create_shared in tests) passes how to bind the shared one.
#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include <epoxy/gl.h>

namespace glint {

class GlProgram;

struct SharedContextHooks {
  std::function<void()> make_current;  // called once on the worker thread before any job
  std::function<void()> release;       // called once on the worker thread when it ends
};

// One program to build. `warm_up` runs on the worker thread with the linked program in use, the
// worker's context current and a vertex array bound: it binds what the renderer's draws bind
// (a framebuffer of the same formats, made there since framebuffers are not shared; uniforms,
// textures, buffers) and draws (or dispatches, for a compute program), so that the driver compiles the code the renderer will use.
struct ProgramJob {
  std::string vertex, fragment, defines;
  std::string compute;  // set instead of vertex and fragment for a compute program
  std::function<void(GlProgram&)> warm_up;

  // Set by the worker; read them only once done() is true.
  bool done() const { return done_.load(std::memory_order_acquire); }
  std::unique_ptr<GlProgram> program;  // null if the build failed
  std::string error;                   // the driver's log when it failed
  double seconds = 0;                  // link and warm-up, wall clock on the worker
  int probes = 0;                      // copies drawn until the driver's cache had the code

 private:
  friend class ProgramWorker;
  std::atomic<bool> done_{false};
};

class ProgramWorker {
 public:
  explicit ProgramWorker(SharedContextHooks context);
  // Finishes the job in progress and drops the queued ones (they never become done).
  ~ProgramWorker();
  ProgramWorker(const ProgramWorker&) = delete;
  ProgramWorker& operator=(const ProgramWorker&) = delete;

  // Queues the job (jobs run one at a time, oldest first). A caller that loses interest just
  // drops its pointer; the program is then deleted on the worker.
  void submit(std::shared_ptr<ProgramJob> job);

 private:
  void run();
  void build(ProgramJob& job);
  double draw_once(ProgramJob& job, GlProgram& program);

  SharedContextHooks context_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::shared_ptr<ProgramJob>> queue_;
  bool stopping_ = false;
  bool healthy_ = true;  // the worker thread bound its context (read and written there only)
  std::string context_error_;
  GLuint vao_ = 0;  // the worker context's own (vertex arrays are not shared)
  std::thread thread_;
};

}  // namespace glint
