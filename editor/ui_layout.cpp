#include "editor/ui_layout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
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

// ImGui keeps dock node sizes in pixels. What they were made for is saved beside them (section
// [Glint][Layout] of layout.ini), so that a layout made at another content scale or for a
// larger window is adapted rather than squeezing the viewport or clipping the panels.
struct LayoutRecord {
  float saved_scale = 0;       // as read from the file; 0: not recorded (an older file)
  ImVec2 saved_size{0, 0};     // the dock space's size it was saved at
  bool loaded = false;         // a file was applied: dock_panels adapts it once
  float scale = 0;             // the content scale the current node sizes are made for
};
LayoutRecord g_record;
constexpr const char* kRecordHandler = "Glint";

void* record_open(ImGuiContext*, ImGuiSettingsHandler*, const char* name) {
  return std::strcmp(name, "Layout") == 0 ? &g_record : nullptr;
}
void record_line(ImGuiContext*, ImGuiSettingsHandler*, void*, const char* line) {
  float a = 0, b = 0;
  if (std::sscanf(line, "Scale=%f", &a) == 1 && std::isfinite(a) && a >= 0.25f && a <= 8) g_record.saved_scale = a;
  else if (std::sscanf(line, "Size=%f,%f", &a, &b) == 2 && std::isfinite(a) && std::isfinite(b) && a >= 1 && b >= 1 &&
           a <= 65536 && b <= 65536)
    g_record.saved_size = ImVec2(a, b);
}
void record_clear(ImGuiContext*, ImGuiSettingsHandler*) {
  g_record.saved_scale = 0;
  g_record.saved_size = ImVec2(0, 0);
}
void record_apply(ImGuiContext*, ImGuiSettingsHandler*) { g_record.loaded = true; }
void record_write(ImGuiContext*, ImGuiSettingsHandler* handler, ImGuiTextBuffer* out) {
  const ImGuiDockNode* root = ImGui::DockBuilderGetNode(dockspace_id());
  if (!(g_record.scale > 0) || !root) return;
  out->appendf("[%s][Layout]\nScale=%.3f\nSize=%.0f,%.0f\n\n", handler->TypeName, g_record.scale, root->Size.x, root->Size.y);
}

// The record's handler in the current context; a context without it is a new one (the app's
// start, each test), whose record starts empty.
void register_record_handler() {
  if (ImGui::FindSettingsHandler(kRecordHandler)) return;
  g_record = LayoutRecord{};
  ImGuiSettingsHandler h;
  h.TypeName = kRecordHandler;
  h.TypeHash = ImHashStr(kRecordHandler);
  h.ClearAllFn = record_clear;
  h.ReadOpenFn = record_open;
  h.ReadLineFn = record_line;
  h.ApplyAllFn = record_apply;
  h.WriteAllFn = record_write;
  ImGui::AddSettingsHandler(&h);
}

// Multiplies every node's sizes under `node` (their pixels) per axis.
void scale_nodes(ImGuiDockNode* node, ImVec2 factor) {
  if (!node) return;
  node->Size = ImVec2(node->Size.x * factor.x, node->Size.y * factor.y);
  node->SizeRef = ImVec2(node->SizeRef.x * factor.x, node->SizeRef.y * factor.y);
  scale_nodes(node->ChildNodes[0], factor);
  scale_nodes(node->ChildNodes[1], factor);
}

// Whether the central node is `node` or below it (ImGui's HasCentralNodeChild is set only
// once the nodes have been updated in a frame, after a layout is loaded).
bool holds_central(const ImGuiDockNode* node) {
  return node && (node->IsCentralNode() || holds_central(node->ChildNodes[0]) || holds_central(node->ChildNodes[1]));
}

// The central node's size when `node` gets `size`, as ImGui splits it (the sibling of the
// branch holding the central node keeps its SizeRef); nullopt without a central node.
std::optional<ImVec2> central_size(const ImGuiDockNode* node, ImVec2 size) {
  if (!node) return std::nullopt;
  if (node->IsCentralNode()) return size;
  if (node->IsLeafNode()) return std::nullopt;
  const int axis = node->SplitAxis == ImGuiAxis_X ? 0 : 1;
  for (int c = 0; c < 2; ++c) {
    const ImGuiDockNode* inner = node->ChildNodes[c];
    const ImGuiDockNode* side = node->ChildNodes[1 - c];
    if (!side || !holds_central(inner)) continue;
    ImVec2 rest = size;
    float& along = axis == 0 ? rest.x : rest.y;
    along = std::max(0.0f, along - std::min(axis == 0 ? side->SizeRef.x : side->SizeRef.y, along) -
                               ImGui::GetStyle().DockingSeparatorSize);
    return central_size(inner, rest);
  }
  return std::nullopt;
}

// The viewport keeps at least this fraction of the dock space on each axis.
constexpr float kMinViewportFraction = 0.25f;

bool viewport_fits(const ImGuiDockNode* root, ImVec2 size) {
  const std::optional<ImVec2> c = central_size(root, size);
  return c && c->x >= kMinViewportFraction * size.x && c->y >= kMinViewportFraction * size.y;
}

// A loaded layout (once), or a new content scale: node sizes follow the scale (panels keep
// their size in ImGui units), then shrink with the window where it is smaller than the one
// the layout was saved for; a layout that still leaves the viewport too little is rebuilt.
// Returns false when the default layout must be built instead.
bool adapt_layout(ImGuiDockNode* root, ImVec2 work, float scale) {
  if (g_record.loaded) {
    g_record.loaded = false;
    g_record.scale = g_record.saved_scale > 0 ? g_record.saved_scale : scale;
    float r = scale / g_record.scale;
    if (r != 1) scale_nodes(root, ImVec2(r, r));
    g_record.scale = scale;
    if (viewport_fits(root, work)) return true;
    if (g_record.saved_size.x > 0) {
      const ImVec2 was(g_record.saved_size.x * r, g_record.saved_size.y * r);
      scale_nodes(root, ImVec2(std::min(1.0f, work.x / was.x), std::min(1.0f, work.y / was.y)));
    }
    return viewport_fits(root, work);
  }
  if (g_record.scale > 0 && scale != g_record.scale) {  // the window moved to another monitor
    const float r = scale / g_record.scale;
    scale_nodes(root, ImVec2(r, r));
    g_record.scale = scale;
    return viewport_fits(root, work);
  }
  return true;
}

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
  register_record_handler();
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  const ImGuiID id = dockspace_id();
  // A layout counts as present once the dock space has been split (built or loaded).
  ImGuiDockNode* node = ImGui::DockBuilderGetNode(id);
  if (!node || node->IsLeafNode() || !adapt_layout(node, viewport->WorkSize, content_scale)) {
    build_default_layout(id, viewport, content_scale);
    g_record.loaded = false;
    g_record.scale = content_scale;
  }
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
  register_record_handler();
  if (text) ImGui::LoadIniSettingsFromMemory(text->data(), text->size());
}

bool save_layout_if_needed(const fs::path& file, bool force, std::string& error) {
  ImGuiIO& io = ImGui::GetIO();
  if (!force && !io.WantSaveIniSettings) return false;
  io.WantSaveIniSettings = false;
  register_record_handler();
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
