// The viewport's move, rotate and scale gizmo (see ui_gizmo.h).
#include "editor/ui_gizmo.h"

#include <algorithm>
#include <cmath>

#include "editor/scene_edits.h"
#include "editor/transform_edits.h"
#include "editor/ui_context.h"

namespace glint {
namespace {

constexpr float kPi = 3.14159265f;
constexpr int kRingPoints = 64;
const ImU32 kAxisColors[3] = {IM_COL32(230, 70, 70, 255), IM_COL32(80, 210, 80, 255), IM_COL32(80, 130, 255, 255)};
const ImU32 kActiveColor = IM_COL32(255, 230, 80, 255);
const ImU32 kShadow = IM_COL32(0, 0, 0, 160);

float segment_distance(ImVec2 p, ImVec2 a, ImVec2 b) {
  ImVec2 ab{b.x - a.x, b.y - a.y}, ap{p.x - a.x, p.y - a.y};
  float len2 = ab.x * ab.x + ab.y * ab.y;
  float t = len2 > 0 ? std::clamp((ap.x * ab.x + ap.y * ab.y) / len2, 0.0f, 1.0f) : 0.0f;
  float dx = ap.x - t * ab.x, dy = ap.y - t * ab.y;
  return std::sqrt(dx * dx + dy * dy);
}

float polyline_distance(ImVec2 p, const std::vector<ImVec2>& ring) {
  float best = 1e30f;
  for (size_t i = 0; i < ring.size(); ++i) best = std::min(best, segment_distance(p, ring[i], ring[(i + 1) % ring.size()]));
  return best;
}

ImVec2 sub(ImVec2 a, ImVec2 b) { return ImVec2(a.x - b.x, a.y - b.y); }
float dot(ImVec2 a, ImVec2 b) { return a.x * b.x + a.y * b.y; }
float length(ImVec2 a) { return std::sqrt(dot(a, a)); }

// The mouse's angle about the gizmo's centre, counter-clockwise as the user sees it (screen y
// points down).
float screen_angle(ImVec2 mouse, ImVec2 origin) { return std::atan2(-(mouse.y - origin.y), mouse.x - origin.x); }

bool is_quad(const Document& doc) {
  return doc.selection.kind == SelectionKind::quad && doc.selection.index >= 0 &&
         doc.selection.index < int(doc.scene.quads.size());
}
bool is_sphere(const Document& doc) {
  return doc.selection.kind == SelectionKind::sphere && doc.selection.index >= 0 &&
         doc.selection.index < int(doc.scene.spheres.size());
}

}  // namespace

const char* gizmo_mode_name(GizmoMode mode) {
  switch (mode) {
    case GizmoMode::move: return "Move";
    case GizmoMode::rotate: return "Rotate";
    case GizmoMode::scale: return "Scale";
  }
  return "";
}

GizmoHandles make_gizmo(const Document& doc, GizmoMode mode, ImVec2 viewport_origin, ImVec2 size) {
  GizmoHandles g;
  const auto center = selection_center(doc.scene, doc.selection);
  if (!center) return g;
  const glm::vec2 view{size.x, size.y};
  const Camera cam = shown_camera(doc.scene, view);
  auto project = [&](glm::vec3 p, ImVec2& out) {
    glm::vec2 v;
    if (!project_to_viewport(cam, view, p, v)) return false;
    out = ImVec2(viewport_origin.x + v.x, viewport_origin.y + v.y);
    return true;
  };
  if (!project(*center, g.origin)) return g;
  // A constant screen size: a fraction of the view height at the object's depth.
  const glm::vec3 forward = glm::normalize(cam.target - cam.position);
  const float depth = std::max(1e-4f, glm::dot(*center - cam.position, forward));
  g.length = depth * std::tan(glm::radians(cam.vfov_deg) * 0.5f) * 0.3f;
  g.center = *center;
  g.visible = true;
  const bool quad = is_quad(doc);
  for (int a = 0; a < 3; ++a) {
    glm::vec3 axis(0);
    axis[a] = 1;
    if (mode == GizmoMode::scale) {
      // Along the quad's own edges (scaling along a world axis would shear a turned quad).
      if (!quad || a == 2) continue;
      const Quad& q = doc.scene.quads[size_t(doc.selection.index)];
      axis = a == 0 ? quad_edge_x(q) : quad_edge_y(q);
      if (axis == glm::vec3(0)) continue;
    }
    if (mode == GizmoMode::rotate) {
      if (!quad) continue;  // a sphere looks the same turned
      // The ring about axis a, parametrised so that the angle grows with a right-handed turn.
      glm::vec3 u(0), v(0);
      u[(a + 1) % 3] = 1;
      v[(a + 2) % 3] = 1;
      std::vector<ImVec2> ring(kRingPoints);
      bool all = true;
      for (int i = 0; i < kRingPoints && all; ++i) {
        const float t = 2 * kPi * float(i) / kRingPoints;
        all = project(*center + g.length * (std::cos(t) * u + std::sin(t) * v), ring[size_t(i)]);
      }
      if (!all) continue;
      g.rings[a] = std::move(ring);
    } else if (!project(*center + axis * g.length, g.ends[a])) {
      continue;
    }
    g.axes[a] = axis;
    g.has_axis[a] = true;
  }
  if (mode == GizmoMode::scale && (quad || is_sphere(doc))) {
    // Outside the arrows' reach: the arrows' length seen square to the view, and a third more.
    const glm::vec3 right = glm::normalize(glm::cross(forward, cam.up));
    ImVec2 side;
    if (project(*center + right * g.length, side)) g.uniform_radius = 1.3f * length(sub(side, g.origin));
  }
  return g;
}

int gizmo_hit(const GizmoHandles& g, GizmoMode mode, ImVec2 mouse) {
  if (!g.visible) return -1;
  const float reach = ui_units(7);
  int best = -1;
  float best_d = reach;
  for (int a = 0; a < 3; ++a) {
    if (!g.has_axis[a]) continue;
    const float d = mode == GizmoMode::rotate ? polyline_distance(mouse, g.rings[a])
                                              : segment_distance(mouse, g.origin, g.ends[a]);
    if (d < best_d) {
      best = a;
      best_d = d;
    }
  }
  if (g.uniform_radius > 0 && std::abs(length(sub(mouse, g.origin)) - g.uniform_radius) < best_d)
    best = kUniformScaleHandle;
  return best;
}

void start_gizmo_drag(const Document& doc, ViewportTools& tools, const GizmoHandles& g, int handle, ImVec2 mouse) {
  tools.gizmo_handle = handle;
  tools.gizmo_start_mouse = mouse;
  tools.gizmo_start_origin = g.origin;
  tools.gizmo_length = g.length;
  const bool axis = handle >= 0 && handle < 3;
  tools.gizmo_axis_world = axis ? g.axes[handle] : glm::vec3(0);
  tools.gizmo_axis_screen = axis ? sub(g.ends[handle], g.origin) : ImVec2(0, 0);
  tools.gizmo_angle = 0;
  tools.gizmo_last_mouse_angle = screen_angle(mouse, g.origin);
  if (is_quad(doc)) tools.gizmo_start_quad = doc.scene.quads[size_t(doc.selection.index)];
  if (is_sphere(doc)) tools.gizmo_start_sphere = doc.scene.spheres[size_t(doc.selection.index)];
}

bool update_gizmo_drag(Document& doc, ViewportTools& tools, ImVec2 mouse) {
  const bool quad = is_quad(doc), sphere = is_sphere(doc);
  if (!quad && !sphere) return false;
  const size_t i = size_t(doc.selection.index);
  const ImVec2 moved = sub(mouse, tools.gizmo_start_mouse);
  const ImVec2 s = tools.gizmo_axis_screen;
  const float s2 = dot(s, s);
  switch (tools.gizmo_mode) {
    case GizmoMode::move: {
      // Along the axis by the mouse motion projected on the arrow's screen direction.
      const float along = s2 > 1e-6f ? dot(moved, s) / s2 * tools.gizmo_length : 0.0f;
      if (quad) doc.scene.quads[i].corners = tools.gizmo_start_quad.corners;
      if (sphere) doc.scene.spheres[i].center = tools.gizmo_start_sphere.center;
      translate(doc.scene, doc.selection, tools.gizmo_axis_world * along);
      return true;
    }
    case GizmoMode::rotate: {
      if (!quad) return false;
      // The mouse's turn about the centre on screen, unwrapped so that a drag may go round more
      // than once; a turn that looks counter-clockwise is right-handed about an axis pointing
      // at the viewer, and the other way about one pointing away.
      const float now = screen_angle(mouse, tools.gizmo_start_origin);
      float step = now - tools.gizmo_last_mouse_angle;
      if (step > kPi) step -= 2 * kPi;
      if (step < -kPi) step += 2 * kPi;
      tools.gizmo_angle += step;
      tools.gizmo_last_mouse_angle = now;
      const Camera cam = doc.scene.camera;
      const Quad& start = tools.gizmo_start_quad;
      const glm::vec3 c = (start.corners[0] + start.corners[1] + start.corners[2] + start.corners[3]) * 0.25f;
      const float facing = glm::dot(tools.gizmo_axis_world, cam.position - c) >= 0 ? 1.0f : -1.0f;
      doc.scene.quads[i].corners = rotate_quad(start, tools.gizmo_axis_world, facing * tools.gizmo_angle).corners;
      return true;
    }
    case GizmoMode::scale: {
      float factor = 1;
      if (tools.gizmo_handle == kUniformScaleHandle) {
        // The ratio of the mouse's distances from the centre now and at the press.
        const float from = length(sub(tools.gizmo_start_mouse, tools.gizmo_start_origin));
        if (from > 1) factor = length(sub(mouse, tools.gizmo_start_origin)) / from;
      } else if (s2 > 1e-6f) {
        // Dragging by the arrow's own screen length adds one: the edge doubles.
        factor = 1 + dot(moved, s) / s2;
      }
      factor = std::max(factor, 0.01f);
      if (sphere) {
        doc.scene.spheres[i].radius = scaled_radius(tools.gizmo_start_sphere.radius, factor);
        return true;
      }
      const float fx = tools.gizmo_handle == 1 ? 1 : factor, fy = tools.gizmo_handle == 0 ? 1 : factor;
      doc.scene.quads[i].corners = scale_quad(tools.gizmo_start_quad, fx, fy).corners;
      return true;
    }
  }
  return false;
}

void draw_gizmo(const GizmoHandles& g, GizmoMode mode, int hover, int active) {
  if (!g.visible) return;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  auto color = [&](int h) { return h == active ? kActiveColor : h < 3 ? kAxisColors[h] : IM_COL32(235, 235, 235, 230); };
  auto thickness = [&](int h) { return ui_units((h == hover || h == active) ? 5.0f : 3.0f); };
  for (int a = 0; a < 3; ++a) {
    if (!g.has_axis[a]) continue;
    const float thick = thickness(a);
    if (mode == GizmoMode::rotate) {
      dl->AddPolyline(g.rings[a].data(), int(g.rings[a].size()), kShadow, ImDrawFlags_Closed, thick + 2);
      dl->AddPolyline(g.rings[a].data(), int(g.rings[a].size()), color(a), ImDrawFlags_Closed, thick);
      continue;
    }
    dl->AddLine(g.origin, g.ends[a], kShadow, thick + 2);
    dl->AddLine(g.origin, g.ends[a], color(a), thick);
    const float r = thick + ui_units(3);
    if (mode == GizmoMode::scale)  // squares mark scale handles, discs move handles
      dl->AddRectFilled(ImVec2(g.ends[a].x - r, g.ends[a].y - r), ImVec2(g.ends[a].x + r, g.ends[a].y + r), color(a));
    else
      dl->AddCircleFilled(g.ends[a], r, color(a));
  }
  if (g.uniform_radius > 0) {
    const float thick = thickness(kUniformScaleHandle);
    dl->AddCircle(g.origin, g.uniform_radius, kShadow, 64, thick + 2);
    dl->AddCircle(g.origin, g.uniform_radius, color(kUniformScaleHandle), 64, thick);
  }
  dl->AddCircleFilled(g.origin, ui_units(4), IM_COL32(255, 255, 255, 220));
}

void draw_gizmo_toolbar(ViewportTools& tools, ImVec2 at) {
  static const char* const kTips[] = {"Move the selection along an axis (G)",
                                      "Rotate a quad about an axis through its centre (R)",
                                      "Scale a quad along its edges or a sphere's radius; the circle scales uniformly (T)"};
  ImGui::SetCursorScreenPos(at);
  for (GizmoMode mode : {GizmoMode::move, GizmoMode::rotate, GizmoMode::scale}) {
    const bool current = tools.gizmo_mode == mode;
    if (current) ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_ButtonActive));
    if (ImGui::Button(gizmo_mode_name(mode)) && tools.gizmo_handle < 0) tools.gizmo_mode = mode;
    if (current) ImGui::PopStyleColor();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", kTips[int(mode)]);
    ImGui::SameLine();
  }
  ImGui::NewLine();
}

}  // namespace glint
