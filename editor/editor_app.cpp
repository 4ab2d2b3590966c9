#include "editor/editor_app.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <epoxy/gl.h>
// epoxy must come before GLFW (which then skips its own GL header).
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>
#include <unistd.h>

#include "editor/app_state.h"
#include "editor/file_dialogs.h"
#include "editor/ui.h"
#include "editor/viewport_renderer.h"
#include "renderer/backend_choice.h"
#include "renderer/image.h"
#include "renderer/program_worker.h"

#ifndef GLINT_SOURCE_DIR
#define GLINT_SOURCE_DIR ""
#endif

namespace glint {
namespace fs = std::filesystem;
namespace {

const char* const kUsage =
    "usage: glint [PROJECT.glint] [--size WxH] [--frames N] [--screenshot FILE.png [--spp N]]\n"
    "             [--backend auto|fragment|compute]\n"
    "\n"
    "Opens the editor (a window: needs a display, e.g. xvfb-run on a server).\n"
    "  --size WxH           window size in screen coordinates (default 1280x800)\n"
    "  --frames N           close after N frames, dropping unsaved changes (for scripts)\n"
    "  --screenshot FILE    render, save a PNG of the whole window and exit: after --frames N\n"
    "                       (default 60), or with --spp N once the viewport has N samples per\n"
    "                       pixel; such runs neither offer a crash recovery nor autosave\n"
    "  --backend B          trace with the fragment or the compute shader; auto (the default)\n"
    "                       takes the faster on this device, as `glint render` does\n";

void glfw_error(int code, const char* text) { std::fprintf(stderr, "glint: GLFW error %d: %s\n", code, text); }

// The whole window as the user sees it, from the default framebuffer's back buffer.
void save_window_png(const fs::path& file, int w, int h) {
  std::vector<unsigned char> rgba(static_cast<size_t>(w) * h * 4);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  Image image;
  image.width = w;
  image.height = h;
  image.pixels.resize(rgba.size());
  for (int y = 0; y < h; ++y)  // GL rows start at the bottom
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c)
        image.pixels[(static_cast<size_t>(y) * w + x) * 4 + c] =
            c == 3 ? 1.0f : rgba[(static_cast<size_t>(h - 1 - y) * w + x) * 4 + c] / 255.0f;
  save_image(file, image);
}

fs::path executable_dir() {
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}

}  // namespace

const char* editor_usage() { return kUsage; }

std::optional<EditorOptions> parse_editor_options(int argc, char** argv, std::string& error) {
  EditorOptions o;
  for (int i = 0; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&]() -> std::optional<std::string> {
      if (i + 1 >= argc) {
        error = a + " needs a value";
        return std::nullopt;
      }
      return std::string(argv[++i]);
    };
    auto integer = [&](long lo, long hi) -> std::optional<long> {
      auto v = value();
      if (!v) return std::nullopt;
      char* end = nullptr;
      long n = std::strtol(v->c_str(), &end, 10);
      if (v->empty() || *end || n < lo || n > hi) {
        error = a + " expects an integer from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got '" + *v + "'";
        return std::nullopt;
      }
      return n;
    };
    if (a == "--screenshot") {
      auto v = value();
      if (!v) return std::nullopt;
      o.screenshot = *v;
      if (o.screenshot.extension() != ".png") {
        error = "--screenshot expects a .png file";
        return std::nullopt;
      }
    } else if (a == "--frames") {
      auto n = integer(1, 1000000);
      if (!n) return std::nullopt;
      o.frames = int(*n);
    } else if (a == "--spp") {
      auto n = integer(1, 1L << 30);
      if (!n) return std::nullopt;
      o.spp = *n;
    } else if (a == "--size") {
      auto v = value();
      if (!v) return std::nullopt;
      int w = 0, h = 0;
      char x = 0, extra = 0;
      if (std::sscanf(v->c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 320 || h < 240 ||
          w > 16384 || h > 16384) {
        error = "--size expects WxH of at least 320x240, got '" + *v + "'";
        return std::nullopt;
      }
      o.width = w;
      o.height = h;
    } else if (a == "--backend") {
      auto v = value();
      if (!v) return std::nullopt;
      if (*v == "auto") o.backend.reset();
      else if (auto b = parse_backend(*v)) o.backend = *b;
      else {
        error = "--backend expects auto, fragment or compute, got '" + *v + "'";
        return std::nullopt;
      }
    } else if (!a.empty() && a[0] == '-') {
      error = "unknown option " + a;
      return std::nullopt;
    } else if (o.project.empty()) {
      o.project = a;
    } else {
      error = "unexpected argument '" + a + "' (one project at a time)";
      return std::nullopt;
    }
  }
  if (o.spp && o.screenshot.empty()) {
    error = "--spp goes with --screenshot";
    return std::nullopt;
  }
  if (!o.screenshot.empty() && !o.frames && !o.spp) o.frames = 60;
  return o;
}

int run_editor(const EditorOptions& options) {
  const bool screenshot_mode = !options.screenshot.empty();
  glfwSetErrorCallback(glfw_error);
  if (!glfwInit()) {
    std::fprintf(stderr, "glint: cannot open a window (no display?); `glint render` works without one\n");
    return 1;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);  // HiDPI: content scale applies to the size
  GLFWwindow* window = glfwCreateWindow(options.width, options.height, "Glint", nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "glint: cannot create an OpenGL 4.5 core window\n");
    glfwTerminate();
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(screenshot_mode ? 0 : 1);
  // A hidden window whose context shares the main one's objects, for the thread that builds
  // specialised trace programs (renderer/program_worker.h). Without it they are built here.
  glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
  GLFWwindow* worker_window = glfwCreateWindow(1, 1, "Glint shader worker", nullptr, window);
  glfwWindowHint(GLFW_VISIBLE, GLFW_TRUE);
  if (!worker_window)
    std::fprintf(stderr, "glint: no second OpenGL context; shader variants compile on the UI thread\n");

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // fixed layout: nothing to remember
  ImGui::StyleColorsDark();
  float xscale = 1, yscale = 1;
  glfwGetWindowContentScale(window, &xscale, &yscale);
  if (xscale > 1.01f) {  // larger text on HiDPI screens where GLFW does not scale framebuffers
    ImGui::GetStyle().ScaleAllSizes(xscale);
    io.FontGlobalScale = xscale;
  }
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 450");

  int exit_code = 0;
  {
    Document doc;
    EditorState state;
    state.native_dialogs = native_file_dialogs_available();
    state.recent_files = load_recent_files();
    state.on_opened_or_saved = [&state](const fs::path& f) { state.recent_files = add_recent_file(f); };
    state.projects_dir = find_projects_dir({executable_dir(), fs::current_path(), fs::path(GLINT_SOURCE_DIR)});

    if (!options.project.empty() && !open_document(doc, state, options.project)) {
      std::fprintf(stderr, "glint: %s\n", state.error.c_str());
      if (screenshot_mode) exit_code = 1;
    }
    // A recovery left by a crashed run is offered (draw_recovery_offer) and this run autosaves,
    // except in screenshot runs, which leave the user's state alone.
    if (!screenshot_mode) {
      state.recovery = find_recovery();
      if (state.recovery)
        std::fprintf(stderr, "glint: offering the unsaved work of a run that did not exit cleanly (%s)\n",
                     state.recovery->file.string().c_str());
      state.autosave.emplace(fs::path(), 30);
    }

    if (worker_window)
      state.shader_worker = std::make_shared<ProgramWorker>(SharedContextHooks{
          [worker_window] { glfwMakeContextCurrent(worker_window); },
          [] { glfwMakeContextCurrent(nullptr); }});
    std::unique_ptr<ViewportRenderer> viewport;
    try {
      if (options.backend) {
        state.trace_backend = *options.backend;
      } else {
        const BackendChoice choice = choose_backend();
        if (!choice.note.empty()) std::fprintf(stderr, "glint: note: %s\n", choice.note.c_str());
        state.trace_backend = choice.backend;
      }
      GpuRendererOptions renderer_options;
      renderer_options.worker = state.shader_worker;
      renderer_options.backend = state.trace_backend;
      viewport = std::make_unique<ViewportRenderer>(renderer_options);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "glint: %s\n", e.what());
      exit_code = 1;
    }
    if (viewport) state.render_viewport = [&](Document& d, EditorState& s) { viewport->render(d, s); };

    int frame = 0;
    std::string title;
    while (viewport && exit_code == 0 && !state.quit_approved) {
      glfwPollEvents();
      if (glfwWindowShouldClose(window)) {
        glfwSetWindowShouldClose(window, GLFW_FALSE);
        if (screenshot_mode) break;
        request_action(doc, state, DocAction::quit);
      }
      int fb_w = 0, fb_h = 0;
      glfwGetFramebufferSize(window, &fb_w, &fb_h);
      if (fb_w <= 0 || fb_h <= 0) {  // minimised
        glfwWaitEventsTimeout(0.1);
        continue;
      }
      viewport->set_framebuffer_size(fb_w, fb_h);

      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();
      draw_editor_ui(doc, state);
      doc.end_frame(ImGui::IsAnyItemActive() || state.interacting);
      ImGui::Render();

      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      glViewport(0, 0, fb_w, fb_h);
      glClearColor(0.1f, 0.1f, 0.11f, 1);
      glClear(GL_COLOR_BUFFER_BIT);
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

      ++frame;
      if (screenshot_mode && ((options.frames && frame >= options.frames) ||
                              (options.spp && state.stats.spp >= options.spp))) {
        try {
          save_window_png(options.screenshot, fb_w, fb_h);
          std::fprintf(stderr, "glint: wrote %s (%dx%d, %d frames, %lld spp, %.1f ms/frame)\n",
                       options.screenshot.string().c_str(), fb_w, fb_h, frame,
                       static_cast<long long>(state.stats.spp), state.stats.ms_per_frame);
        } catch (const std::exception& e) {
          std::fprintf(stderr, "glint: %s\n", e.what());
          exit_code = 1;
        }
        break;
      }
      glfwSwapBuffers(window);
      if (std::string t = doc.window_title(); t != title) {
        title = t;
        glfwSetWindowTitle(window, title.c_str());
      }
      if (state.autosave) state.autosave->update(doc, glfwGetTime());
      if (!screenshot_mode && options.frames && frame >= options.frames) break;
    }
    if (state.autosave) state.autosave->finish();
    state.thumbnails.clear();
    state.export_job.reset();
    viewport.reset();
    state.shader_worker.reset();  // joins the thread before its window goes
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  if (worker_window) glfwDestroyWindow(worker_window);
  glfwDestroyWindow(window);
  glfwTerminate();
  return exit_code;
}

}  // namespace glint
