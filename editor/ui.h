// The editor's panels. Each takes the Document and the EditorState and needs only an ImGui
// context (and a current GL context for thumbnails): no GLFW, so tests drive them headlessly.
//
// draw_editor_ui() is the first step of a frame (editor/editor_frame.h): it lays out the dock
// space (editor/ui_layout.h) and runs the panels in order: shortcuts, menu bar, status bar,
// outliner, properties, render statistics, the viewport's mouse input (selection, gizmo,
// camera), the export dialog, the document modals, and last the recovery offer. It edits the document and this state; it does not
// render. The viewport image it shows is the one show_viewport_image() puts under the panels
// once the viewport has rendered the edited scene.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <imgui.h>

#include "editor/document.h"
#include "editor/export_job.h"
#include "editor/file_dialogs.h"
#include "editor/recent_and_recovery.h"
#include "editor/render_stats_history.h"
#include "editor/shown_values.h"
#include "editor/thumbnails.h"
#include "editor/viewport_frame.h"
#include "renderer/render_options.h"
#include "renderer/trace_backend.h"

namespace glint {

class ProgramWorker;

// What a chosen file is for (native dialog or the typed-path prompt).
enum class FilePurpose { open_project, save_project_as, texture_slot, add_texture, environment, export_output, import_scene, export_scene };
// Actions behind the unsaved-changes guard.
// open_example: an example project as an untitled copy (open_example_copy).
enum class DocAction { none, new_document, open_dialog, open_path, open_example, import_dialog, quit };

// The viewport panel: where it is this frame, how it previews, and what it shows.
struct ViewportView {
  // In ImGui units (points), set by draw_editor_ui each frame from the window's size.
  ImVec2 pos{0, 0}, size{1, 1};
  // Trace pixels per ImGui unit (io.DisplayFramebufferScale): HiDPI traces at framebuffer pixels.
  float framebuffer_scale = 1;
  ViewportResolution resolution = ViewportResolution::automatic;
  bool denoise = false;  // show the denoised preview (editor/viewport_denoiser.h)
  // How the viewport and exports sample (not saved in the project; see render_options.h).
  RenderOptions estimator;
  // Region render: only this part of the viewport (fractions of it) takes samples; none: all
  // (editor/ui_region.cpp). Not saved, not undone, not applied to exports.
  std::optional<FractionRect> region;
  bool error_map = false;  // overlay the per-pixel estimated error
  // > 0: the viewport pauses its accumulation at this estimated relMSE (not saved).
  double target_error = 0;
  // This frame's render once the viewport has rendered (before: the last frame's).
  ViewportFrame frame;
  // Set by draw_viewport: the film Export writes (framed in the viewport), the selection's
  // outline in screen coordinates, and whether the user is busy (the preview waits to refine).
  Film film;
  std::vector<ImVec2> outline;
  bool user_active = false;
};

// What a drag on the viewport's gizmo does (editor/ui_gizmo.h).
enum class GizmoMode { move, rotate, scale };

// The viewport's tools and the drags in progress.
struct ViewportTools {
  bool focus_tool = false;   // a click sets the focus distance instead of selecting
  bool interacting = false;  // a gizmo, camera or fly gesture is in progress (one undo step)
  // The camera moved by navigation this frame (orbit, pan, zoom, fly): such moves merge into one
  // undo step (Document::end_frame); a typed value or a click-to-focus is a step of its own.
  bool navigated = false;
  GizmoMode gizmo_mode = GizmoMode::move;
  int gizmo_handle = -1;  // handle being dragged (an axis, a ring, the uniform scale circle), -1 none
  int gizmo_hover = -1;
  // Measured at the press: the mouse, the gizmo's centre on screen, the dragged arrow's screen
  // vector and world direction, the arrows' world length, and the object as it was.
  ImVec2 gizmo_start_mouse{0, 0};
  ImVec2 gizmo_start_origin{0, 0};
  ImVec2 gizmo_axis_screen{0, 0};
  glm::vec3 gizmo_axis_world{0};
  float gizmo_length = 1;
  Sphere gizmo_start_sphere;
  Quad gizmo_start_quad;
  // A rotation drag: the angle turned so far and the mouse's last angle about the centre.
  float gizmo_angle = 0;
  float gizmo_last_mouse_angle = 0;
  bool region_tool = false;      // the next left drag draws the render region (Ctrl+B)
  bool region_dragging = false;
  ImVec2 region_start{0, 0};
  int camera_button = -1;  // mouse button driving the camera, -1 none
  bool camera_moved = false;
  ImVec2 press_pos{0, 0};
};

// Opening, saving and choosing files: the unsaved-changes guard, the typed-path prompt.
struct DocumentFlow {
  DocAction pending = DocAction::none;
  std::filesystem::path pending_path;
  bool open_unsaved_prompt = false;
  bool quit_approved = false;  // the app loop ends when set
  bool native_dialogs = false; // tinyfd has a graphical backend
  std::vector<std::filesystem::path> recent_files;
  std::function<void(const std::filesystem::path&)> on_opened_or_saved;  // recent-file list
  std::filesystem::path projects_dir;  // the examples of File > Examples

  // The typed-path prompt (when no native dialog exists).
  struct PathPrompt {
    bool request_open = false;
    FilePurpose purpose = FilePurpose::open_project;
    std::string title;
    char buffer[1024] = {};
  } prompt;
  int slot_material = -1;  // the texture slot a chosen file goes to
  int slot_index = 0;      // 0 colour, 1 emission, 2 roughness

  // The native dialog open now, on its own thread (editor/file_dialogs.h): the window keeps
  // redrawing and a modal blocks the editor's input until it answers (poll_file_dialog).
  AsyncFileDialog dialog;
  FilePurpose dialog_purpose = FilePurpose::open_project;
  AsyncFileDialog::Runner dialog_runner;  // empty: tinyfd (tests put a stand-in here)
};

// A transient line in the status bar and a modal for errors.
struct Messages {
  std::string message;
  double message_until = 0;
  std::string error;
  bool open_error = false;
  bool error_enter_released = false;  // Enter closes the error box only after a release in it
  // A problem with the editor's own files (settings, layout, recent files, recovery): the
  // defaults were used or a file was not written. Shown beside the transient message.
  std::string note;
  double note_until = 0;
};

// The export dialog and the job it started.
struct ExportUi {
  bool show = false;
  ExportSettings settings;
  std::unique_ptr<ExportJob> job;
  std::string message;
  // Where the dialog drew the running export's progress bar and its time left this frame
  // (screen coordinates): the bar's hover help goes below the bar, never over the time left.
  ImVec2 progress_min{0, 0}, progress_max{0, 0};
  ImVec2 time_left_min{0, 0}, time_left_max{0, 0};
};

// Deleting a material that objects use waits for the user's answer.
struct DeletePrompt {
  Selection material;  // the material to delete once confirmed
  std::vector<std::string> users;
  bool request_open = false;
};

// Renaming in the outliner.
struct Renaming {
  Selection item;
  char buffer[256] = {};
};

struct EditorState {
  ViewportView viewport;
  ViewportTools tools;
  DocumentFlow flow;
  Messages messages;
  ExportUi export_ui;
  Renaming renaming;
  DeletePrompt delete_prompt;
  // The properties panel's Euler angles and emission form, kept as the user set them.
  QuadRotationView shown_rotation;
  EmissionView shown_emission;
  bool show_controls = false;  // Help > Controls
  bool show_about = false;     // Help > About

  // Remembered between runs (editor/recent_and_recovery.h); the app saves them when this is
  // set and they change (tests leave it empty and the user's config alone).
  EditorSettings settings;
  std::function<void(const EditorSettings&)> on_settings_changed;

  // Crash recovery: the work that sessions which did not exit cleanly left, offered one after
  // the other once the panels exist (each removed when answered), and this run's autosave
  // (none in tests and screenshot runs).
  std::vector<Recovery> recoveries;
  std::optional<Autosave> autosave;

  // Builds specialised trace programs off the UI thread for the viewport and exports (null:
  // they are built on the UI thread; see renderer/program_worker.h).
  std::shared_ptr<ProgramWorker> shader_worker;
  // The entry point the viewport and exports trace with (renderer/backend_choice.h).
  TraceBackend trace_backend = TraceBackend::fragment;
  ThumbnailCache thumbnails;
  RenderStatsHistory stats_history;  // the Render statistics panel's curves
  // Monitor content scale the UI is drawn at (editor/ui_context.h); the default layout's
  // panel sizes are multiplied by it.
  float content_scale = 1;
};

// Step 1 of editor_frame: every panel's input and widgets, in order. Renders nothing.
void draw_editor_ui(Document& doc, EditorState& state);

void handle_shortcuts(Document& doc, EditorState& state);
void draw_main_menu(Document& doc, EditorState& state);
void draw_outliner(Document& doc, EditorState& state);
void draw_properties(Document& doc, EditorState& state);
// The properties panel's camera views (editor/ui_camera_views.cpp); the ImGui label of view
// `index`'s widget `what` ("Go", "Set", "X", "" for its name field).
void draw_camera_views(Document& doc, EditorState& state);
std::string view_widget_id(const char* what, int index);
// The material panel's Preset combo (editor/ui_material_presets.cpp).
void draw_material_preset_combo(Material& material);
void draw_status_bar(Document& doc, EditorState& state);
void draw_render_stats(Document& doc, EditorState& state);
// One curve of the Render statistics panel, `height` ImGui units tall; log_y: a log10 y axis
// (for errors). Any series can be fed to it (editor/render_stats_history.h).
void plot_time_series(const char* plot_id, const TimeSeries& series, bool log_y, float height);
void draw_document_modals(Document& doc, EditorState& state);
void draw_recovery_offer(Document& doc, EditorState& state);
void draw_export_dialog(Document& doc, EditorState& state);
// The viewport's mouse input and overlays (gizmo, focus tool); the image goes under it.
void draw_viewport(Document& doc, EditorState& state);
// Region render and the error map (editor/ui_region.cpp): Ctrl+B arms the region tool and
// Ctrl+Alt+B clears the region; region_drag takes the viewport's left drag while the tool is
// armed (true: the mouse is its); the toolbar's Region, Clear region and Error map buttons end
// at `top_right`; the overlays (the map, its legend, the region's frame) go over the image.
void handle_region_shortcuts(EditorState& state);
bool region_drag(EditorState& state, ImVec2 origin, ImVec2 size, bool hovered);
void clear_region(EditorState& state);
void draw_region_toolbar(EditorState& state, ImVec2 top_right);
void draw_region_overlays(const ViewportView& view, ImDrawList* draw_list);
// What the viewport and the status line say before the first image.
inline constexpr const char* kCompilingShaders = "Compiling shaders...";
// Puts this frame's viewport image (and why it is not updating, if so) under the panels; before
// the first image, kCompilingShaders in its middle.
void show_viewport_image(const ViewportView& view);
// The viewport's request for this frame: the panel's size in framebuffer pixels; no tracing
// while an export runs.
ViewportRequest viewport_request(const EditorState& state);
bool export_running(const EditorState& state);
// The export dialog's first settings: the film's size, a file named after the project in the
// remembered export folder (else the user's Pictures folder or home, never beside the project).
ExportSettings default_export_settings(const Document& doc, const EditorState& state);
// "Viewport aspect": keeps the width, takes the viewport's aspect, and frames what it shows.
void use_viewport_aspect(ExportSettings& settings, const ViewportView& view);
// The scene an export renders: `scene`, with the camera the viewport shows where the settings
// frame the viewport (use_viewport_aspect) and their size still has its aspect.
Scene export_scene(const Scene& scene, const ExportSettings& settings);
// "about 12 s left" from the fraction done and the seconds so far.
std::string export_eta(double progress, double elapsed_seconds);
void step_export(EditorState& state, double slice_seconds);  // one slice of a running export

// The status bar's line, piece by piece: the frame figures, then an autosave failure (shown
// until an autosave succeeds), a note about the editor's own files, then the transient message
// or the export's progress.
struct StatusPiece {
  std::string text;
  ImVec4 color;
  int priority = 0;  // 0: kept longest (the spp, messages, errors); higher ones go first
};
std::vector<StatusPiece> status_line(const EditorState& state, double now_s);
// The pieces that fit in `width` pixels at the current font, in their order: the least
// important (highest priority number) are left out first; where the most important left still
// do not fit, the last one is cut short with "...". Needs an ImGui frame (text sizes).
std::vector<StatusPiece> fit_status_line(std::vector<StatusPiece> pieces, float width);

// Deletes a sphere, quad, texture or unused material at once; a material in use is deleted only
// after the prompt (naming its users) is confirmed. Afterwards nothing is selected.
void delete_item(Document& doc, EditorState& state, Selection what);
void draw_delete_prompt(Document& doc, EditorState& state);
// The settings changed: tells on_settings_changed.
void settings_changed(EditorState& state);
// The Help menu's windows: the controls sheet and About.
void draw_help_windows(EditorState& state);
// The rows of Help > Controls: every mouse gesture, key and menu path with an effect of its own.
struct ControlLine {
  const char* input;
  const char* action;
};
std::span<const ControlLine> editor_controls();
// A file dropped on the window: a project opens (asking about unsaved changes), an .hdr or
// .exr becomes the environment, another image the colour texture of the selected object's
// material (or of the selected material). Returns what it did, for the status bar.
std::string drop_file(Document& doc, EditorState& state, const std::filesystem::path& file);

// Document actions (menus, keys and tests). request_action asks about unsaved changes first.
void request_action(Document& doc, EditorState& state, DocAction action, std::filesystem::path path = {});
bool open_document(Document& doc, EditorState& state, const std::filesystem::path& file);
// File > Import scene... / Export scene... (editor/ui_scene_exchange.cpp, renderer/scene_exchange.h):
// a Mitsuba 3 or pbrt-v4 scene as a new untitled document, or the document written as one. The
// warnings go to stderr, their count and the first to the status bar. False (with the error
// shown, the document untouched) on failure.
bool import_document(Document& doc, EditorState& state, const std::filesystem::path& file);
bool export_document(const Document& doc, EditorState& state, const std::filesystem::path& file);
bool save_document(Document& doc, EditorState& state, bool save_as);
void new_document(Document& doc, EditorState& state);
// Asks for a file (native dialog, else the typed-path prompt) and applies it once chosen (a
// native dialog answers in a later frame: poll_file_dialog).
void choose_file(Document& doc, EditorState& state, FilePurpose purpose);
// While a native dialog is open: a modal that blocks the editor's input; once it answers, the
// chosen file is applied (a cancelled save-as ends the action that asked for it).
void poll_file_dialog(Document& doc, EditorState& state);
void apply_chosen_file(Document& doc, EditorState& state, FilePurpose purpose, const std::string& file);
// Where a file chooser starts: a folder for opening and for images (never a pre-filled
// project file name), the current file for saving and exporting.
std::string file_dialog_start(const Document& doc, const EditorState& state, FilePurpose purpose);
void show_error(EditorState& state, const std::string& message);
void show_message(EditorState& state, const std::string& message);
// A problem with the editor's own files (Messages::note) in the status line for 10 s; notes
// that come while one shows are joined to it.
void show_note(EditorState& state, const std::string& note);

// File > Examples: the project files in projects_dir, sorted by name (empty when it is unknown
// or unreadable).
std::vector<std::filesystem::path> example_projects(const std::filesystem::path& projects_dir);
// Opens an example as an untitled copy: its assets resolve from the example's folder, and Save
// asks for a path, so that Ctrl+S never overwrites a shipped example.
bool open_example_copy(Document& doc, EditorState& state, const std::filesystem::path& file);
// Searches upwards from these folders for projects/default.glint; returns the projects folder.
std::filesystem::path find_projects_dir(const std::vector<std::filesystem::path>& starts);

// Viewport maths (ui_viewport.cpp): world point -> viewport pixel (relative to its top-left);
// false when behind the camera.
bool project_to_viewport(const Camera& camera, glm::vec2 viewport_size, glm::vec3 p, glm::vec2& out);
// The camera the viewport shows: the scene's, widened to frame the film (editor/film_frame.h).
Camera shown_camera(const Scene& scene, glm::vec2 viewport_size);
// The outline of a selected sphere (its silhouette circle, 64 points) or quad (its 4 corners)
// in viewport pixels; empty when nothing outlinable is selected or it is behind the camera.
std::vector<glm::vec2> selection_outline(const Scene& scene, Selection sel, glm::vec2 viewport_size);
// Selects (or focuses, with the focus tool or Ctrl) at a viewport position in [0,1]^2.
void click_viewport(Document& doc, EditorState& state, glm::vec2 film, bool focus);

}  // namespace glint
