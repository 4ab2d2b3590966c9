#include "renderer/program_worker.h"

#include <chrono>
#include <exception>
#include <thread>

#include "renderer/gl_program.h"
#include "renderer/stopwatch.h"

namespace glint {

ProgramWorker::ProgramWorker(SharedContextHooks context) : context_(std::move(context)) {
  thread_ = std::thread([this] { run(); });
}

ProgramWorker::~ProgramWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    queue_.clear();
  }
  wake_.notify_all();
  thread_.join();
}

void ProgramWorker::submit(std::shared_ptr<ProgramJob> job) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.push_back(std::move(job));
  }
  wake_.notify_one();
}

void ProgramWorker::run() {
  try {
    context_.make_current();
    glCreateVertexArrays(1, &vao_);
  } catch (const std::exception& e) {
    healthy_ = false;
    context_error_ = e.what();
  }
  for (;;) {
    std::shared_ptr<ProgramJob> job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) break;
      job = std::move(queue_.front());
      queue_.pop_front();
    }
    // A job nobody waits for any more is skipped: its scene was edited again meanwhile.
    if (job.use_count() == 1) continue;
    build(*job);
    job->done_.store(true, std::memory_order_release);
  }
  if (healthy_) {
    glDeleteVertexArrays(1, &vao_);
    context_.release();
  }
}

// Runs the job's draw with the program; returns its seconds (the driver's compile at the first
// draw, when it does that).
double ProgramWorker::draw_once(ProgramJob& job, GlProgram& program) {
  const auto start = std::chrono::steady_clock::now();
  glViewport(0, 0, 1, 1);
  glBindVertexArray(vao_);
  glUseProgram(program.id());
  job.warm_up(program);
  glUseProgram(0);
  glFinish();
  return seconds_since(start);
}

namespace {

std::unique_ptr<GlProgram> link(const ProgramJob& job) {
  if (!job.compute.empty()) return GlProgram::compute(job.compute, job.defines);
  return std::make_unique<GlProgram>(job.vertex, job.fragment, job.defines);
}

}  // namespace

void ProgramWorker::build(ProgramJob& job) {
  if (!healthy_) {
    job.error = "the shader worker has no OpenGL context: " + context_error_;
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  try {
    auto program = link(job);
    if (job.warm_up) {
      const double first = draw_once(job, *program);
      // llvmpipe writes the compiled code to its disk cache from a thread of minimum priority,
      // which a busy machine can starve: the renderer's first draw would then compile again,
      // on the UI thread (seen in gl.GlProgramWorker.NoFrameWaitsForAStructuralEditsProgram
      // while builds ran: a 7.6 s frame). So a fresh copy of the program, whose first draw
      // must find the code somewhere, is drawn until that draw is fast: then the cache has it.
      // A first draw under 50 ms compiled nothing worth moving (a driver that compiles at link
      // time). After a few tries the job ends anyway; the renderer then compiles at its first
      // draw, as it would without the worker.
      for (int probe = 0; first > 0.05 && probe < 5; ++probe) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20 << probe));
        auto copy = link(job);
        ++job.probes;
        if (draw_once(job, *copy) < first / 4) break;
      }
    }
    job.program = std::move(program);
  } catch (const std::exception& e) {
    job.error = e.what();
  }
  job.seconds = seconds_since(start);
}

}  // namespace glint
