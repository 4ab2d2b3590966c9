// Building trace programs on a worker thread in a shared context (renderer/program_worker.h):
// the renderer keeps drawing meanwhile, switches when the build is done, gets the same image,
// and the driver's first-draw compile has moved off the calling thread.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <memory>
#include <random>
#include <thread>

#include "renderer/gl_program.h"
#include "renderer/program_worker.h"
#include "renderer/project_file.h"
#include "tests/gl/gl_test_support.h"

namespace glint {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// A worker with its own context shared with the test's. The shared context outlives the worker
// (members are destroyed in reverse order).
struct WorkerFixture {
  std::unique_ptr<HeadlessGLContext> shared = test::ensure_gl_context().create_shared();
  std::shared_ptr<ProgramWorker> worker = std::make_shared<ProgramWorker>(SharedContextHooks{
      [this] { shared->make_current(); }, [this] { shared->release_current(); }});
  ~WorkerFixture() { worker.reset(); }
};

bool wait_done(const ProgramJob& job, double seconds) {
  auto start = Clock::now();
  while (!job.done()) {
    if (seconds_since(start) > seconds) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

TEST(GlProgramWorker, RendererSwitchesToTheWorkersProgramAndGetsTheSameImage) {
  test::ensure_gl_context();
  WorkerFixture f;
  Scene scene = load_project(GLINT_SOURCE_DIR "/projects/cornell_box.glint");
  scene.render.seed = 5;
  GpuRendererOptions options;
  options.worker = f.worker;
  GpuRenderer r(options);
  r.sync(scene, 16, 16);
  int generic_passes = 0;
  auto start = Clock::now();
  for (;;) {
    r.trace(1);
    if (!r.last_pass_generic()) break;
    ++generic_passes;
    ASSERT_LT(seconds_since(start), 60.0) << "the worker's program never became ready";
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_GE(generic_passes, 1) << "the first pass must not wait for the build";
  EXPECT_EQ(r.last_pass_defines(), shader_defines(r.features()));

  GpuRendererOptions generic;
  generic.force_generic_shader = true;
  GpuRenderer g(generic);
  g.sync(scene, 16, 16);
  for (int64_t i = 0; i < r.sample_count(); ++i) g.trace(1);
  // As in shader_variants_test: programs that differ only by removed branches agree to float
  // rounding of a few hundred operations (relative 1e-4).
  EXPECT_LE(test::max_relative_difference(r.read_accumulation(), g.read_accumulation()), 1e-4);
}

TEST(GlProgramWorker, ReportsACompileErrorWithTheDriversLog) {
  test::ensure_gl_context();
  WorkerFixture f;
  auto job = std::make_shared<ProgramJob>();
  job->vertex = "fullscreen.vert";
  job->fragment = "trace.frag";
  job->defines = "#error deliberately broken\n";
  f.worker->submit(job);
  ASSERT_TRUE(wait_done(*job, 60));
  EXPECT_EQ(job->program, nullptr);
  EXPECT_NE(job->error.find("trace.frag failed to compile"), std::string::npos) << job->error;
}

TEST(GlProgramWorker, StopsPromptlyWithJobsQueuedAndSkipsAbandonedOnes) {
  test::ensure_gl_context();
  auto start = Clock::now();
  std::shared_ptr<ProgramJob> kept;
  {
    WorkerFixture f;
    for (int i = 0; i < 3; ++i) {
      auto job = std::make_shared<ProgramJob>();
      job->vertex = "fullscreen.vert";
      job->fragment = "tonemap.frag";
      f.worker->submit(job);  // abandoned at once: never built
    }
    kept = std::make_shared<ProgramJob>();
    kept->vertex = "fullscreen.vert";
    kept->fragment = "tonemap.frag";
    f.worker->submit(kept);
    ASSERT_TRUE(wait_done(*kept, 60));
    EXPECT_NE(kept->program, nullptr) << kept->error;
  }
  // The kept program outlives the worker and its context; deleting it here is legal because
  // the test's context shares it.
  kept.reset();
  EXPECT_LT(seconds_since(start), 60.0);
}

// Mesa's llvmpipe finds the worker's compiled code through its on-disk shader cache, so with
// the cache disabled the worker still links off the UI thread, but the first draw here compiles
// again.
bool shader_cache_disabled() {
  const char* v = std::getenv("MESA_SHADER_CACHE_DISABLE");
  return v && std::string(v) != "false" && std::string(v) != "0";
}

// The timing tests measure what llvmpipe does (compile at the first draw); a GPU driver that
// compiles at link time has no first-draw cost to move (an H100: 0.3-1.5 ms cold).
#define SKIP_UNLESS_LLVMPIPE_WITH_CACHE()                                                 \
  do {                                                                                    \
    if (shader_cache_disabled()) GTEST_SKIP() << "MESA_SHADER_CACHE_DISABLE is set";      \
    if (!on_llvmpipe())                                                                   \
      GTEST_SKIP() << "timed for llvmpipe, not " << gl_renderer_name();                   \
  } while (0)

// A 1x1 RGBA32F target, as the worker draws into, to time a program's first draw here.
struct OnePixelTarget {
  GLuint vao = 0, texture = 0, fbo = 0;
  OnePixelTarget() {
    glCreateVertexArrays(1, &vao);
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, GL_RGBA32F, 1, 1);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, texture, 0);
  }
  ~OnePixelTarget() {
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &texture);
    glDeleteVertexArrays(1, &vao);
  }
  double draw_seconds(GlProgram& p) const {
    auto start = Clock::now();
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, 1, 1);
    glBindVertexArray(vao);
    glUseProgram(p.id());
    p.set("u_samples_per_pass", 0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glFinish();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return seconds_since(start);
  }
};

// The first draw of a trace program new to the driver, on this thread: what a frame would wait
// for without the worker.
double cold_first_draw_seconds(const std::string& defines) {
  GlProgram program("fullscreen.vert", "trace.frag", defines);
  return OnePixelTarget().draw_seconds(program);
}

std::string nonce_define() {
  static std::random_device seed;
  return "#define GLINT_TEST_NONCE " + std::to_string(seed()) + "u\n";
}

// What the editor's viewport does each frame (one small pass, then the display), timed frame by
// frame across a structural edit, with programs new to the driver: no frame waits for a new
// variant's compile. The bound is half of a cold first draw of such a variant measured here and
// now, so that it scales with the machine's load. A frame of a few ms can still be descheduled
// for 0.1-1.5 s on this shared machine (seen in CI with a build running beside it, before the
// edit as much as after), so a trial that exceeds the bound is repeated with new programs, up
// to 3 trials: a frame that waits for the compile does so in every trial.
struct StructuralEditTrial {
  double cold = 0, before_edit = 0, after_edit = 0;
  bool passed() const { return before_edit < cold / 2 && after_edit < cold / 2; }
};

StructuralEditTrial time_a_structural_edit() {
  WorkerFixture f;
  Scene scene = load_project(GLINT_SOURCE_DIR "/projects/cornell_box.glint");
  const std::string nonce = nonce_define();
  StructuralEditTrial trial;
  trial.cold = cold_first_draw_seconds(shader_defines(scene_features(scene)) + nonce_define());
  GpuRendererOptions options;
  options.worker = f.worker;
  options.extra_defines = nonce;
  GpuRenderer r(options);
  // Runs frames until the specialised program has drawn 3 of them; the slowest frame's seconds.
  auto slowest_frame = [&r] {
    double slowest = 0;
    int specialised = 0;
    auto start = Clock::now();
    while (specialised < 3 && seconds_since(start) < 60) {
      auto frame = Clock::now();
      r.trace(1);
      r.update_display();
      glFinish();
      slowest = std::max(slowest, seconds_since(frame));
      if (!r.last_pass_generic()) ++specialised;
    }
    EXPECT_EQ(specialised, 3) << "the specialised program never became ready";
    return slowest;
  };
  r.sync(scene, 16, 16);
  r.trace(1);  // the generic program's own first-draw compile, before the timing
  glFinish();
  trial.before_edit = slowest_frame();
  // Structural edit: a texture, so the new variant has texture fetches and a bound array.
  scene.textures.push_back({.name = "wood", .path = "assets/wood_color.png"});
  scene.materials[0].color_texture = "wood";
  EXPECT_TRUE(r.sync(scene, 16, 16).accumulation_reset);
  trial.after_edit = slowest_frame();
  std::printf("cold first draw %.4f s; slowest frame %.4f s before the edit, %.4f s after\n",
              trial.cold, trial.before_edit, trial.after_edit);
  return trial;
}

TEST(GlProgramWorker, NoFrameWaitsForAStructuralEditsProgram) {
  test::ensure_gl_context();
  SKIP_UNLESS_LLVMPIPE_WITH_CACHE();
  StructuralEditTrial trial;
  int trials = 0;
  do {
    trial = time_a_structural_edit();
    ++trials;
  } while (!trial.passed() && trials < 3);
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", trial.cold);
  RecordProperty("cold_first_draw_seconds", text);
  std::snprintf(text, sizeof text, "%.4f", trial.after_edit);
  RecordProperty("slowest_frame_after_edit_seconds", text);
  RecordProperty("trials", trials);
  EXPECT_LT(trial.before_edit, trial.cold / 2) << "in each of " << trials << " trials";
  EXPECT_LT(trial.after_edit, trial.cold / 2) << "in each of " << trials << " trials";
}

// The point of the worker on llvmpipe: the first draw with a program costs the JIT compile
// (0.6-1 s for a trace variant); after the worker drew with it in a shared context, the
// driver finds the compiled code and the calling thread's first draw is cheap. A nonce in the
// defines makes both programs new to Mesa's shader cache. Timings go to the test's XML
// properties; the assertion is only that warming helps by 2x, far inside what it measures.
TEST(GlProgramWorker, FirstDrawAfterTheWorkerIsCheaperThanACold) {
  test::ensure_gl_context();
  SKIP_UNLESS_LLVMPIPE_WITH_CACHE();
  WorkerFixture f;
  // The Cornell box's variant: smaller than the generic program, so the test is quicker.
  const std::string defines =
      shader_defines(scene_features(load_project(GLINT_SOURCE_DIR "/projects/cornell_box.glint")));
  const double cold_seconds = cold_first_draw_seconds(defines + nonce_define());

  auto job = std::make_shared<ProgramJob>();
  job->vertex = "fullscreen.vert";
  job->fragment = "trace.frag";
  job->defines = defines + nonce_define();
  job->warm_up = [](GlProgram& p) { OnePixelTarget().draw_seconds(p); };  // made in its context
  f.worker->submit(job);
  ASSERT_TRUE(wait_done(*job, 120));
  ASSERT_NE(job->program, nullptr) << job->error;
  const double warm_seconds = OnePixelTarget().draw_seconds(*job->program);

  char text[64];
  std::snprintf(text, sizeof text, "%.4f", cold_seconds);
  RecordProperty("cold_first_draw_seconds", text);
  std::snprintf(text, sizeof text, "%.4f", warm_seconds);
  RecordProperty("warmed_first_draw_seconds", text);
  std::snprintf(text, sizeof text, "%.4f", job->seconds);
  RecordProperty("worker_build_seconds", text);
  std::printf("first draw: cold %.4f s, after the worker %.4f s (worker %.4f s, %d probes)\n",
              cold_seconds, warm_seconds, job->seconds, job->probes);
  EXPECT_LT(warm_seconds, cold_seconds / 2);
}

}  // namespace
}  // namespace glint
