// The viewport's transform gizmo, drawn with ImGui's draw list over the image. Three modes
// (toolbar buttons, keys G R T): move arrows along the world axes; rotation rings about the world
// axes through the centre (quads); scale arrows along a quad's two edges and a circle for
// uniform scale (quads; spheres: the circle scales the radius). A drag edits the object from its
// state at the press, so it is exact however many frames it takes, and the document makes the
// whole drag one undo step. The maths is editor/transform_edits.h.
#pragma once

#include <vector>

#include "editor/ui.h"

namespace glint {

constexpr int kUniformScaleHandle = 3;

// The selection's gizmo for a mode, in screen coordinates (ImGui units).
struct GizmoHandles {
  bool visible = false;  // something movable is selected and in front of the camera
  glm::vec3 center{0};
  float length = 1;  // world length of the arrows and radius of the rings
  ImVec2 origin{0, 0};
  // Handles 0-2: move and rotate: the world axes; scale: a quad's edges p0->p2, p0->p1 (no third).
  glm::vec3 axes[3] = {};
  bool has_axis[3] = {false, false, false};
  ImVec2 ends[3] = {};                // the arrows' tips
  std::vector<ImVec2> rings[3];       // rotate: each ring as a closed polyline
  float uniform_radius = 0;           // scale: the circle's radius, 0 when there is none
};

GizmoHandles make_gizmo(const Document& doc, GizmoMode mode, ImVec2 viewport_origin, ImVec2 viewport_size);
// The handle under the mouse (0-2, kUniformScaleHandle), the nearest within a few units; -1 none.
int gizmo_hit(const GizmoHandles& gizmo, GizmoMode mode, ImVec2 mouse);
// A press on `handle`: remembers the object and the geometry the drag is measured against.
void start_gizmo_drag(const Document& doc, ViewportTools& tools, const GizmoHandles& gizmo, int handle, ImVec2 mouse);
// The mouse held at `mouse`: sets the object from its state at the press. Returns false when
// the selection is gone (the drag ends).
bool update_gizmo_drag(Document& doc, ViewportTools& tools, ImVec2 mouse);
void draw_gizmo(const GizmoHandles& gizmo, GizmoMode mode, int hover, int active);
// The mode buttons at the viewport's top-left corner (drawn before the viewport's input item,
// so a click on them is theirs).
void draw_gizmo_toolbar(ViewportTools& tools, ImVec2 at);
const char* gizmo_mode_name(GizmoMode mode);

}  // namespace glint
