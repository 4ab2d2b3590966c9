// The viewport panel: click to select or focus, the move/rotate/scale gizmo (editor/ui_gizmo.h),
// mouse navigation (orbit, pan, zoom), and the rendered image under them.
#include <algorithm>
#include <cmath>

#include "editor/camera_control.h"
#include "editor/film_frame.h"
#include "editor/picking.h"
#include "editor/scene_edits.h"
#include "editor/ui.h"
#include "editor/ui_context.h"
#include "editor/ui_gizmo.h"
#include "editor/ui_layout.h"

namespace glint {

bool project_to_viewport(const Camera& camera, glm::vec2 size, glm::vec3 p, glm::vec2& out) {
  // The inverse of the shader's camera_ray (shaders/lib/camera.glsl) through the lens centre.
  glm::vec3 forward = glm::normalize(camera.target - camera.position);
  glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  glm::vec3 up = glm::cross(right, forward);
  glm::vec3 v = p - camera.position;
  float z = glm::dot(v, forward);
  if (z <= 1e-6f) return false;
  float tan_half = std::tan(glm::radians(camera.vfov_deg) * 0.5f);
  float aspect = size.x / std::max(1.0f, size.y);
  float sx = glm::dot(v, right) / z / (tan_half * aspect);
  float sy = glm::dot(v, up) / z / tan_half;
  out = {(sx + 1) * 0.5f * size.x, (1 - sy) * 0.5f * size.y};
  return true;
}

Camera shown_camera(const Scene& scene, glm::vec2 viewport_size) {
  return viewport_camera(scene.camera, viewport_size, scene.film);
}

std::vector<glm::vec2> selection_outline(const Scene& scene, Selection sel, glm::vec2 size) {
  const Camera cam = shown_camera(scene, size);
  std::vector<glm::vec2> out;
  auto add = [&](glm::vec3 p) {
    glm::vec2 v;
    if (!project_to_viewport(cam, size, p, v)) return false;
    out.push_back(v);
    return true;
  };
  if (sel.kind == SelectionKind::sphere && sel.index >= 0 && sel.index < int(scene.spheres.size())) {
    // The silhouette is the circle where the cone from the eye touches the sphere: centre
    // c - r^2/d u, radius r sqrt(1 - r^2/d^2), in the plane normal to u (the view direction).
    const Sphere& s = scene.spheres[sel.index];
    glm::vec3 to = s.center - cam.position;
    float d = glm::length(to);
    if (!(d > s.radius * 1.0001f)) return {};  // the eye is inside
    glm::vec3 u = to / d;
    glm::vec3 centre = s.center - u * (s.radius * s.radius / d);
    float radius = s.radius * std::sqrt(1 - (s.radius * s.radius) / (d * d));
    glm::vec3 a = glm::normalize(glm::cross(u, std::abs(u.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)));
    glm::vec3 b = glm::cross(u, a);
    for (int i = 0; i < 64; ++i) {
      float t = 2 * 3.14159265f * i / 64;
      if (!add(centre + radius * (std::cos(t) * a + std::sin(t) * b))) return {};
    }
  } else if (sel.kind == SelectionKind::quad && sel.index >= 0 && sel.index < int(scene.quads.size())) {
    const Quad& q = scene.quads[sel.index];
    for (int c : {0, 1, 3, 2})  // around the edge (p3 is opposite p0)
      if (!add(q.corners[c])) return {};
  }
  return out;
}

void click_viewport(Document& doc, EditorState& state, glm::vec2 film, bool focus) {
  float aspect = state.viewport.size.x / std::max(1.0f, state.viewport.size.y);
  Scene shown = doc.scene;  // picks through the camera the viewport shows
  shown.camera = shown_camera(doc.scene, {state.viewport.size.x, state.viewport.size.y});
  auto hit = pick(shown, film, aspect);
  if (focus) {
    if (!hit) return show_message(state, "Nothing there to focus on");
    doc.scene.camera.focus_distance = focus_distance_for(doc.scene.camera, hit->point);
    char text[96];
    std::snprintf(text, sizeof text, "Focus distance %.3f (on %s)", doc.scene.camera.focus_distance,
                  name_of(doc.scene, hit->what).c_str());
    show_message(state, text);
    return;
  }
  doc.selection = hit ? hit->what : Selection{};
}

// A gizmo drag or a camera gesture under way: move, orbit, pan; a click without a drag selects
// (or focuses); the wheel dollies.
static void continue_viewport_gesture(Document& doc, EditorState& state, ImVec2 origin, ImVec2 size,
                                      bool hovered, bool focusing) {
  ImGuiIO& io = ImGui::GetIO();
  ViewportTools& tools = state.tools;
  if (tools.gizmo_handle >= 0) {
    if (ImGui::IsMouseDown(ImGuiMouseButton_Left) && update_gizmo_drag(doc, tools, io.MousePos))
      tools.interacting = true;
    else
      tools.gizmo_handle = -1;
  } else if (tools.camera_button >= 0) {
    int b = tools.camera_button;
    if (ImGui::IsMouseDown(b)) {
      ImVec2 d = io.MouseDelta;
      float moved = std::hypot(io.MousePos.x - tools.press_pos.x, io.MousePos.y - tools.press_pos.y);
      if (moved > 3) tools.camera_moved = true;
      if (tools.camera_moved && (d.x != 0 || d.y != 0)) {
        Camera& cam = doc.scene.camera;
        bool panning = b == ImGuiMouseButton_Middle || io.KeyShift;
        // Orbit as in Blender, as if the scene were grabbed: a drag right turns it right, a drag
        // up tilts its near side up (the camera goes down); View > Invert vertical orbit flips that.
        if (panning) pan(cam, {-d.x / size.y, d.y / size.y});
        else orbit(cam, -d.x * 0.008f, d.y * 0.008f * (state.settings.invert_vertical_orbit ? -1 : 1));
        tools.navigated = true;
      }
      if (tools.camera_moved) tools.interacting = true;
    } else {
      if (b == ImGuiMouseButton_Left && !tools.camera_moved) {
        glm::vec2 film{(tools.press_pos.x - origin.x) / size.x, (tools.press_pos.y - origin.y) / size.y};
        click_viewport(doc, state, film, focusing);
      }
      tools.camera_button = -1;
    }
  }
  if (hovered && io.MouseWheel != 0) {
    dolly(doc.scene.camera, std::pow(0.85f, io.MouseWheel));
    tools.navigated = true;
  }

}

// The selection's outline, the gizmo and the active tool's hint, and whether the user is busy
// (the viewport then traces a fluid preview).
static void draw_viewport_overlays(Document& doc, EditorState& state, ImVec2 origin, ImVec2 size) {
  ImGuiIO& io = ImGui::GetIO();
  ViewportTools& tools = state.tools;
  // The image goes under this window once the viewport has rendered (show_viewport_image),
  // with the film frame and the selection's outline, which are drawn there too.
  ImDrawList* dl = ImGui::GetWindowDrawList();
  ImVec2 end(origin.x + size.x, origin.y + size.y);
  state.viewport.film = doc.scene.film;
  state.viewport.outline.clear();
  for (glm::vec2 p : selection_outline(doc.scene, doc.selection, {size.x, size.y}))
    state.viewport.outline.push_back(ImVec2(origin.x + p.x, origin.y + p.y));
  state.viewport.user_active = ImGui::IsAnyItemActive() || tools.interacting || io.MouseWheel != 0 ||
                               io.MouseDelta.x != 0 || io.MouseDelta.y != 0 || ImGui::IsAnyMouseDown();
  const GizmoHandles gizmo = make_gizmo(doc, tools.gizmo_mode, origin, size);  // where the object is now
  draw_gizmo(gizmo, tools.gizmo_mode, tools.gizmo_hover, tools.gizmo_handle);
  const char* hint = nullptr;
  if (tools.region_tool) hint = "Region: drag a rectangle to render only there (Ctrl+Alt+B clears)";
  else if (tools.focus_tool) hint = "Focus tool: click a surface";
  else if (tools.gizmo_mode == GizmoMode::rotate && doc.selection.kind == SelectionKind::sphere)
    hint = "Rotate: a sphere looks the same turned (select a quad)";
  if (hint) dl->AddText(ImVec2(origin.x + 10, end.y - ImGui::GetFrameHeight() - 4), IM_COL32(255, 230, 120, 255), hint);
}

void draw_viewport(Document& doc, EditorState& state) {
  ImGuiIO& io = ImGui::GetIO();
  // A dockable window without a background (the image goes under it, show_viewport_image);
  // its input and overlays live in a child window that covers it, drawn above that image.
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
  const bool open = ImGui::Begin(kViewportWindow, nullptr,
                                 ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse |
                                     ImGuiWindowFlags_NoBackground | ImGuiWindowFlags_NoCollapse);
  ImGui::PopStyleVar();
  if (!open) {
    ImGui::End();
    return;
  }
  ImVec2 origin = ImGui::GetCursorScreenPos();
  ImVec2 size = ImGui::GetContentRegionAvail();
  size.x = std::max(size.x, 1.0f);
  size.y = std::max(size.y, 1.0f);
  state.viewport.pos = origin;
  state.viewport.size = size;
  ImGui::BeginChild("##viewport overlay", size, ImGuiChildFlags_None,
                    ImGuiWindowFlags_NoBackground | ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);

  // The gizmo's mode buttons first: where they are, they take the mouse from the item below.
  const float inset = ui_units(6);
  draw_gizmo_toolbar(state.tools, ImVec2(origin.x + inset, origin.y + inset));
  draw_region_toolbar(state, ImVec2(origin.x + size.x - inset, origin.y + inset));
  ImGui::SetCursorScreenPos(origin);
  // One item over the whole image: ImGui then knows a drag here is in progress.
  ImGui::InvisibleButton("##viewport", size,
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight |
                             ImGuiButtonFlags_MouseButtonMiddle);
  const bool hovered = ImGui::IsItemHovered();
  ViewportTools& tools = state.tools;
  GizmoHandles gizmo = make_gizmo(doc, tools.gizmo_mode, origin, size);
  tools.gizmo_hover = -1;
  // Ctrl+click and the focus tool always focus, even on the gizmo.
  const bool focusing = tools.focus_tool || io.KeyCtrl;
  if (hovered && !focusing && tools.gizmo_handle < 0 && tools.camera_button < 0)
    tools.gizmo_hover = gizmo_hit(gizmo, tools.gizmo_mode, io.MousePos);

  // Presses start a region, a gizmo drag or a camera gesture.
  if (region_drag(state, origin, size, hovered)) {
  } else if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left) && tools.gizmo_hover >= 0) {
    start_gizmo_drag(doc, tools, gizmo, tools.gizmo_hover, io.MousePos);
  } else if (hovered && tools.camera_button < 0) {
    for (int b : {ImGuiMouseButton_Left, ImGuiMouseButton_Right, ImGuiMouseButton_Middle})
      if (ImGui::IsMouseClicked(b)) {
        tools.camera_button = b;
        tools.camera_moved = false;
        tools.press_pos = io.MousePos;
        break;
      }
  }

  continue_viewport_gesture(doc, state, origin, size, hovered, focusing);
  draw_viewport_overlays(doc, state, origin, size);
  ImGui::EndChild();
  ImGui::End();
}

ViewportRequest viewport_request(const EditorState& state) {
  const ViewportView& v = state.viewport;
  ViewportRequest r;
  r.width = std::max(1, int(std::lround(v.size.x * v.framebuffer_scale)));
  r.height = std::max(1, int(std::lround(v.size.y * v.framebuffer_scale)));
  r.resolution = v.resolution;
  r.estimator = v.estimator;
  r.target_error = v.target_error;
  r.denoise = v.denoise;
  r.trace = !export_running(state);  // the export gets the device while it runs
  r.film_width = v.film.width;
  r.film_height = v.film.height;
  r.user_active = v.user_active;
  r.region = v.region;
  r.error_map = v.error_map;
  return r;
}

void show_viewport_image(const ViewportView& view) {
  // Appends to the viewport window (its Begin a second time this frame): the window's own draw
  // list is drawn before its overlay child, so the gizmo and texts lie on top of the image. The
  // image is the one rendered this frame for view.size, so a resize never shows a stale or
  // stretched frame. A hidden viewport (another tab in front) draws nothing.
  const bool open = ImGui::Begin(kViewportWindow);
  if (open) {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 origin = view.pos;
    const ImVec2 end(origin.x + view.size.x, origin.y + view.size.y);
    if (view.frame.display_texture)
      dl->AddImage(static_cast<ImTextureID>(view.frame.display_texture), origin, end);
    else
      dl->AddRectFilled(origin, end, IM_COL32(20, 20, 24, 255));
    // Before the first image (the trace programs compile for seconds on a slow device).
    if (!view.frame.display_texture && view.frame.stats.scene_problem.empty()) {
      const char* text = kCompilingShaders;
      const ImVec2 t = ImGui::CalcTextSize(text);
      dl->AddText(ImVec2(origin.x + (view.size.x - t.x) * 0.5f, origin.y + (view.size.y - t.y) * 0.5f),
                  IM_COL32(230, 230, 230, 255), text);
    }
    // The film frame: what Export writes is inside; the margins are dimmed.
    const FilmRect f = film_rect({view.size.x, view.size.y}, view.film);
    const ImVec2 f0(origin.x + f.offset.x, origin.y + f.offset.y);
    const ImVec2 f1(f0.x + f.size.x, f0.y + f.size.y);
    const ImU32 dim = IM_COL32(0, 0, 0, 150);
    if (f0.y - origin.y > 0.5f) {
      dl->AddRectFilled(origin, ImVec2(end.x, f0.y), dim);
      dl->AddRectFilled(ImVec2(origin.x, f1.y), end, dim);
    }
    if (f0.x - origin.x > 0.5f) {
      dl->AddRectFilled(origin, ImVec2(f0.x, end.y), dim);
      dl->AddRectFilled(ImVec2(f1.x, origin.y), end, dim);
    }
    dl->AddRect(f0, f1, IM_COL32(255, 255, 255, 90));
    draw_region_overlays(view, dl);
    // The selection's outline (Blender's orange), over the image.
    if (view.outline.size() >= 2) {
      dl->AddPolyline(view.outline.data(), int(view.outline.size()), IM_COL32(0, 0, 0, 140), ImDrawFlags_Closed, 3.5f);
      dl->AddPolyline(view.outline.data(), int(view.outline.size()), IM_COL32(255, 160, 40, 255), ImDrawFlags_Closed, 1.5f);
    }
    if (!view.frame.stats.scene_problem.empty())
      dl->AddText(ImVec2(origin.x + 10, origin.y + 10 + ImGui::GetFrameHeightWithSpacing()), IM_COL32(255, 120, 90, 255),
                  ("Not rendering: " + view.frame.stats.scene_problem).c_str());
  }
  ImGui::End();
}

}  // namespace glint
