// The editor's window layout: a dock space over the main window, below the menu bar and above
// the status bar, holding the panels. The first time (no saved layout) it is built with Dear
// ImGui's DockBuilder: outliner left, properties right, render statistics below the viewport,
// the viewport in the centre, side widths in ImGui units times the content scale. The user can
// then drag, resize, tab and float the panels; the layout is saved in the user's config folder
// (never the working directory), atomically, and restored at the next start. ImGui keeps the
// panels' sizes in pixels: the content scale and the dock space's size are saved with them, and
// a layout restored at another scale has its sizes multiplied by the ratio (a panel keeps its
// size in ImGui units), one restored on a smaller window than it was saved for shrinks with it
// where the viewport would keep less than a quarter of the window, and one that still leaves
// the viewport less than that is replaced by the default layout. A window moved to a monitor
// of another scale rescales the panels the same way.
#pragma once

#include <filesystem>
#include <string>

#include <imgui.h>

namespace glint {

// The panels' window names (dock targets, and the keys in the saved layout).
inline constexpr const char* kOutlinerWindow = "Outliner";
inline constexpr const char* kPropertiesWindow = "Properties";
inline constexpr const char* kViewportWindow = "Viewport";
inline constexpr const char* kStatsWindow = "Render statistics";

// Default sizes in ImGui units at content scale 1.
inline constexpr float kOutlinerWidth = 270, kPropertiesWidth = 340, kStatsHeight = 170;

// config_dir()/layout.ini; `dir` overrides config_dir() (tests).
std::filesystem::path layout_file_path(const std::filesystem::path& dir = {});

// The dock space for this frame, over the main viewport's work area (call after the menu and
// status bars, before the panels' Begin). Builds the default layout when none was loaded, and
// adapts a loaded one to `content_scale` and the window (above).
// Returns the dock space's id.
ImGuiID dock_panels(float content_scale);
// Throws away the current layout; the next dock_panels() builds the default one.
void reset_layout();

// Loads a saved layout into the current context (call before the first frame). A missing file
// is no error; one that cannot be read (read_state_file: a FIFO, a folder, a file over the
// cap) is reported in `error` and the default layout is used.
void load_layout(const std::filesystem::path& file, std::string& error);
// Writes the layout when ImGui asks (io.WantSaveIniSettings) or when `force`, with
// write_state_file_atomically (a link at the path is refused, never written through); best
// effort: an error (a read-only home, a link) goes to `error` and never stops the editor.
// Returns true when written.
bool save_layout_if_needed(const std::filesystem::path& file, bool force, std::string& error);

}  // namespace glint
