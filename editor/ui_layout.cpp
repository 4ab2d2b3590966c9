#include "editor/ui_layout.h"

#include <algorithm>
#include <optional>

#include <imgui_internal.h>  // DockBuilder*: the docking branch's layout API

#include "editor/recent_and_recovery.h"
#include "renderer/atomic_file.h"
#include "renderer/state_file.h"

namespace glint {
namespace fs = std::filesystem;
namespace {

// The dock space's id: a hash of its name, the same wherever in the ID stack it is asked for.
ImGuiID dockspace_id() { return ImHashStr("Glint dock space"); }

void build_default_layout(ImGuiID dockspace, const ImGuiViewport* viewport, float scale) {
  ImGui::DockBuilderRemoveNode(dockspace);
  ImGui::DockBuilderAddNode(dockspace, ImGuiDockNodeFlags_DockSpace);
  ImGui::DockBuilderSetNodeSize(dockspace, viewport->WorkSize);
  const ImVec2 size = viewport->WorkSize;
  // Side panels keep their widths in ImGui units (times the scale) unless the window is too
  // narrow, where they keep at most 30% and 35% of it.
  auto ratio = [](float want, float total, float cap) { return std::clamp(want / std::max(total, 1.0f), 0.05f, cap); };
  ImGuiID centre = dockspace;
  const ImGuiID left = ImGui::DockBuilderSplitNode(centre, ImGuiDir_Left, ratio(kOutlinerWidth * scale, size.x, 0.3f), nullptr, &centre);
  const float rest_w = size.x * (1 - ratio(kOutlinerWidth * scale, size.x, 0.3f));
  const ImGuiID right = ImGui::DockBuilderSplitNode(centre, ImGuiDir_Right,
                                                    ratio(kPropertiesWidth * scale, rest_w, 0.5f), nullptr, &centre);
  const ImGuiID bottom = ImGui::DockBuilderSplitNode(centre, ImGuiDir_Down, ratio(kStatsHeight * scale, size.y, 0.3f), nullptr, &centre);
  ImGui::DockBuilderDockWindow(kOutlinerWindow, left);
  ImGui::DockBuilderDockWindow(kPropertiesWindow, right);
  ImGui::DockBuilderDockWindow(kStatsWindow, bottom);
  ImGui::DockBuilderDockWindow(kViewportWindow, centre);
  // The viewport is the central node: its tab bar hides (a small triangle brings it back).
  if (ImGuiDockNode* node = ImGui::DockBuilderGetNode(centre)) node->LocalFlags |= ImGuiDockNodeFlags_AutoHideTabBar;
  ImGui::DockBuilderFinish(dockspace);
}

}  // namespace

fs::path layout_file_path(const fs::path& dir) { return config_dir(dir) / "layout.ini"; }

ImGuiID dock_panels(float content_scale) {
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  const ImGuiID id = dockspace_id();
  // A layout counts as present once the dock space has been split (built or loaded).
  const ImGuiDockNode* node = ImGui::DockBuilderGetNode(id);
  if (!node || node->IsLeafNode()) build_default_layout(id, viewport, content_scale);
  // The central node lets the viewport image (drawn under the windows) show through.
  return ImGui::DockSpaceOverViewport(id, viewport, ImGuiDockNodeFlags_PassthruCentralNode);
}

void reset_layout() {
  ImGui::DockBuilderRemoveNode(dockspace_id());
  ImGui::MarkIniSettingsDirty();
}

void load_layout(const fs::path& file, std::string& error) {
  error.clear();
  std::optional<std::string> text;
  try {
    text = read_state_file(file);
  } catch (const StateFileError& e) {
    error = std::string(e.what()) + "; using the default layout";
    return;
  }
  if (text) ImGui::LoadIniSettingsFromMemory(text->data(), text->size());
}

bool save_layout_if_needed(const fs::path& file, bool force, std::string& error) {
  ImGuiIO& io = ImGui::GetIO();
  if (!force && !io.WantSaveIniSettings) return false;
  io.WantSaveIniSettings = false;
  size_t size = 0;
  const char* text = ImGui::SaveIniSettingsToMemory(&size);
  try {
    std::error_code ec;
    fs::create_directories(file.parent_path(), ec);
    write_state_file_atomically(file, text, size);
    error.clear();
    return true;
  } catch (const std::exception& e) {
    error = std::string(e.what()) + "; the window layout is not saved";
    return false;
  }
}

}  // namespace glint
