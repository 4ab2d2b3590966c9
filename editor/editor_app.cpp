#include "editor/editor_app.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>

#include <epoxy/gl.h>
// epoxy must come before GLFW (which then skips its own GL header).
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>
#include <unistd.h>

#include "editor/editor_frame.h"
#include "editor/file_dialogs.h"
#include "editor/recent_and_recovery.h"
#include "editor/scene_edits.h"
#include "editor/ui.h"
#include "editor/ui_context.h"
#include "editor/ui_layout.h"
#include "editor/viewport_renderer.h"
#include "renderer/backend_choice.h"
#include "renderer/image.h"
#include "renderer/parse_number.h"
#include "renderer/program_worker.h"

#ifndef GLINT_SOURCE_DIR
#define GLINT_SOURCE_DIR ""
#endif

namespace glint {
namespace fs = std::filesystem;
namespace {

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

struct Windows {
  GLFWwindow* main = nullptr;
  GLFWwindow* worker = nullptr;  // hidden, sharing main's objects; null: none could be made
};

// The editor's window (OpenGL 4.5 core, current on this thread) and a hidden window whose
// context shares its objects, for the thread that builds specialised trace programs
// (renderer/program_worker.h). Without that one they are built on the UI thread.
std::optional<Windows> open_windows(const EditorOptions& options, bool screenshot_mode) {
  glfwSetErrorCallback(glfw_error);
  if (!glfwInit()) {
    std::fprintf(stderr, "glint: cannot open a window (no display?); `glint render` works without one\n");
    return std::nullopt;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);  // HiDPI: content scale applies to the size
  Windows w;
  w.main = glfwCreateWindow(options.width, options.height, "Glint", nullptr, nullptr);
  if (!w.main) {
    std::fprintf(stderr, "glint: cannot create an OpenGL 4.5 core window\n");
    glfwTerminate();
    return std::nullopt;
  }
  glfwMakeContextCurrent(w.main);
  glfwSwapInterval(screenshot_mode ? 0 : 1);
  glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
  w.worker = glfwCreateWindow(1, 1, "Glint shader worker", nullptr, w.main);
  glfwWindowHint(GLFW_VISIBLE, GLFW_TRUE);
  if (!w.worker)
    std::fprintf(stderr, "glint: no second OpenGL context; shader variants compile on the UI thread\n");
  return w;
}

void close_windows(const Windows& w) {
  if (w.worker) glfwDestroyWindow(w.worker);
  glfwDestroyWindow(w.main);
  glfwTerminate();
}

// The monitor's content scale (GLINT_CONTENT_SCALE overrides it).
float window_content_scale(GLFWwindow* window) {
  if (const float s = content_scale_override()) return s;
  float xscale = 1, yscale = 1;
  glfwGetWindowContentScale(window, &xscale, &yscale);
  return xscale;
}

// A problem with the editor's own files (settings, layout, recent files, recovery): on stderr
// and in the status line. Nothing when `note` is empty.
void report_note(EditorState& state, const std::string& note) {
  if (note.empty()) return;
  std::fprintf(stderr, "glint: %s\n", note.c_str());
  show_note(state, note);
}

// The layout comes from the user's config folder, except in screenshot runs, which show the
// default layout and leave the user's state alone.
void start_imgui(GLFWwindow* window, EditorState& state, const fs::path& layout_file) {
  state.content_scale = window_content_scale(window);
  create_ui_context(state.content_scale);
  state.content_scale = content_scale();
  if (!layout_file.empty()) {
    std::string error;
    load_layout(layout_file, error);
    report_note(state, error);
  }
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 450");
}

// A window moved to a monitor of another scale re-rasterises the font and rescales the style.
void follow_content_scale(GLFWwindow* window, EditorState& state) {
  set_content_scale(window_content_scale(window));
  state.content_scale = content_scale();
}

// `last_error`: the last save's problem, reported again only when it changes (ImGui asks to
// save every few seconds while windows move).
void save_layout(EditorState& state, const fs::path& layout_file, bool force, std::string& last_error) {
  if (layout_file.empty()) return;
  std::string error;
  if (save_layout_if_needed(layout_file, force, error)) last_error.clear();
  if (error.empty() || error == last_error) return;
  last_error = error;
  report_note(state, error);
}

void stop_imgui() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  destroy_ui_context();
}

// The state at start: file dialogs, recent files, the examples folder, the command line's
// project, and (except in screenshot runs, which leave the user's state alone) the recoveries
// that sessions which did not exit cleanly left, offered by draw_recovery_offer, and this run's
// autosave. Problems with the editor's own files are notes. Returns false when a screenshot
// run's project does not open.
bool start_session(Document& doc, EditorState& state, const EditorOptions& options, GLFWwindow* worker_window) {
  const bool screenshot_mode = !options.screenshot.empty();
  bool ok = true;
  state.flow.native_dialogs = native_file_dialogs_available();
  std::string note;
  state.flow.recent_files = load_recent_files(note);
  report_note(state, note);
  state.flow.on_opened_or_saved = [&state](const fs::path& f) {
    std::string problem;
    state.flow.recent_files = add_recent_file(f, problem);
    report_note(state, problem);
  };
  // Installed, the examples are in ../share/glint/projects from bin/glint (cmake/Packaging.cmake).
  state.flow.projects_dir = find_projects_dir({executable_dir() / ".." / "share" / "glint", executable_dir(),
                                               fs::current_path(), fs::path(GLINT_SOURCE_DIR)});
  // The user's settings (preview mode, export folder); screenshot runs read but never write them.
  state.settings = load_editor_settings(note);
  report_note(state, note);
  state.viewport.resolution = state.settings.preview;
  if (!screenshot_mode)
    state.on_settings_changed = [&state](const EditorSettings& s) {
      std::string problem;
      save_editor_settings(s, problem);
      report_note(state, problem);
    };
  if (!options.project.empty() && !open_document(doc, state, options.project)) {
    std::fprintf(stderr, "glint: %s\n", state.messages.error.c_str());
    if (screenshot_mode) ok = false;
  }
  if (!options.select.empty()) {
    if (const auto found = find_object(doc.scene, options.select)) {
      doc.selection = *found;
    } else {
      std::fprintf(stderr, "glint: --select: no sphere or quad is named '%s'\n", options.select.c_str());
      if (screenshot_mode) ok = false;
    }
  }
  if (!screenshot_mode) {
    std::vector<std::string> notes;
    state.recoveries = find_recoveries(notes);
    for (const std::string& n : notes) report_note(state, n);
    for (const Recovery& r : state.recoveries)
      std::fprintf(stderr, "glint: offering the unsaved work of a run that did not exit cleanly (%s)\n",
                   r.file.string().c_str());
    state.autosave.emplace(fs::path(), 30);
  }
  if (worker_window)
    state.shader_worker = std::make_shared<ProgramWorker>(SharedContextHooks{
        [worker_window] { glfwMakeContextCurrent(worker_window); },
        [] { glfwMakeContextCurrent(nullptr); }});
  return ok;
}

// Null (and a message) when the trace shader cannot be built.
// The viewport renderer, with the backend forced by --backend or chosen for this device
// (renderer/backend_choice.h); exports trace with the same one.
std::unique_ptr<ViewportRenderer> make_viewport(EditorState& state, const EditorOptions& options) {
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
    return std::make_unique<ViewportRenderer>(renderer_options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint: %s\n", e.what());
    return nullptr;
  }
}

// Clean exit: the autosave's file goes; GL objects go while the context exists; the worker's
// thread is joined before its window goes.
void end_session(EditorState& state, std::unique_ptr<ViewportRenderer>& viewport) {
  if (state.autosave) state.autosave->finish();
  state.thumbnails.clear();
  state.export_ui.job.reset();
  viewport.reset();
  state.shader_worker.reset();
}

// Files dropped on the window since the last frame (GLFW calls back from glfwPollEvents, on
// this thread).
std::vector<fs::path> g_dropped;
void on_drop(GLFWwindow*, int count, const char** paths) {
  for (int i = 0; i < count; ++i) g_dropped.emplace_back(paths[i]);
}

enum class Poll { frame, minimised, stop };

// Window events. A close request becomes the quit action (behind the unsaved-changes guard);
// a screenshot run just stops. `fb_w`, `fb_h`: the framebuffer's size.
Poll poll_window(GLFWwindow* window, Document& doc, EditorState& state, bool screenshot_mode, int& fb_w, int& fb_h) {
  glfwPollEvents();
  if (glfwWindowShouldClose(window)) {
    glfwSetWindowShouldClose(window, GLFW_FALSE);
    if (screenshot_mode) return Poll::stop;
    request_action(doc, state, DocAction::quit);
  }
  glfwGetFramebufferSize(window, &fb_w, &fb_h);
  if (fb_w <= 0 || fb_h <= 0) {
    glfwWaitEventsTimeout(0.1);
    return Poll::minimised;
  }
  return Poll::frame;
}

void begin_imgui_frame() {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

// ImGui's draw data (the viewport image and the panels) into the window's back buffer.
void draw_imgui(int fb_w, int fb_h) {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, fb_w, fb_h);
  glClearColor(0.1f, 0.1f, 0.11f, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

bool screenshot_due(const EditorOptions& options, int frame, const EditorState& state) {
  return (options.frames && frame >= options.frames) ||
         (options.spp && state.viewport.frame.stats.spp >= options.spp);
}

// Saves the back buffer; returns the exit code.
int save_screenshot(const EditorOptions& options, int fb_w, int fb_h, int frame, const FrameStats& stats) {
  try {
    save_window_png(options.screenshot, fb_w, fb_h);
    std::fprintf(stderr, "glint: wrote %s (%dx%d, %d frames, %lld spp, %.1f ms/frame)\n",
                 options.screenshot.string().c_str(), fb_w, fb_h, frame, static_cast<long long>(stats.spp),
                 stats.ms_per_frame);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint: %s\n", e.what());
    return 1;
  }
}

// Two frames (the dock layout is in place from the second) drawn before the viewport renderer
// compiles its programs: the window shows the panels and "Compiling shaders..." meanwhile.
void show_startup_frames(GLFWwindow* window, Document& doc, EditorState& state) {
  for (int i = 0; i < 2; ++i) {
    glfwPollEvents();
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(window, &fb_w, &fb_h);
    if (fb_w <= 0 || fb_h <= 0) return;
    begin_imgui_frame();
    editor_frame_before_viewport(doc, state);
    draw_imgui(fb_w, fb_h);
    glfwSwapBuffers(window);
  }
}

void update_title(GLFWwindow* window, const Document& doc, std::string& title) {
  if (std::string t = doc.window_title(); t != title) {
    title = t;
    glfwSetWindowTitle(window, title.c_str());
  }
}

}  // namespace

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
      const std::optional<long> n = parse_integer(*v, lo, hi);
      if (!n) error = integer_expected(a, lo, hi, *v);
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
    } else if (a == "--select") {
      auto v = value();
      if (!v) return std::nullopt;
      o.select = *v;
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
  const std::optional<Windows> windows = open_windows(options, screenshot_mode);
  if (!windows) return 1;
  glfwSetDropCallback(windows->main, on_drop);
  const fs::path layout_file = screenshot_mode ? fs::path() : layout_file_path();
  int exit_code = 0;
  {
    Document doc;
    EditorState state;
    start_imgui(windows->main, state, layout_file);
    if (!start_session(doc, state, options, windows->worker)) exit_code = 1;
    show_startup_frames(windows->main, doc, state);
    std::unique_ptr<ViewportRenderer> viewport = make_viewport(state, options);
    if (!viewport) exit_code = 1;

    int frame = 0;
    std::string title, layout_error;
    while (exit_code == 0 && !state.flow.quit_approved) {
      int fb_w = 0, fb_h = 0;
      const Poll poll = poll_window(windows->main, doc, state, screenshot_mode, fb_w, fb_h);
      if (poll == Poll::stop) break;
      if (poll == Poll::minimised) continue;
      follow_content_scale(windows->main, state);
      begin_imgui_frame();
      for (const fs::path& file : std::exchange(g_dropped, {})) drop_file(doc, state, file);
      // Widgets edit the document, the viewport renders it, the export steps, undo is derived,
      // ImGui's draw data is built (editor_frame.h); then it is drawn.
      editor_frame(doc, state, *viewport);
      draw_imgui(fb_w, fb_h);
      ++frame;
      if (screenshot_mode && screenshot_due(options, frame, state)) {
        exit_code = save_screenshot(options, fb_w, fb_h, frame, state.viewport.frame.stats);
        break;
      }
      glfwSwapBuffers(windows->main);
      update_title(windows->main, doc, title);
      if (state.autosave) state.autosave->update(doc, glfwGetTime());
      save_layout(state, layout_file, false, layout_error);
      if (!screenshot_mode && options.frames && frame >= options.frames) break;
    }
    end_session(state, viewport);
    save_layout(state, layout_file, true, layout_error);
    stop_imgui();
  }
  close_windows(*windows);
  return exit_code;
}

}  // namespace glint
