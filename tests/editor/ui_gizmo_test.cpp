// The viewport's rotate and scale gizmo driven with simulated mouse and keys (the fixture:
// ui_test_fixture.h): a drag on a ring turns a quad, a drag on a square or the circle scales
// it (or a sphere's radius), each drag is one undo step, and the modes switch by key and button.
#include <gtest/gtest.h>

#include <cmath>

#include "editor/scene_edits.h"
#include "editor/transform_edits.h"
#include "editor/ui_gizmo.h"
#include "ui_test_fixture.h"

namespace glint {
namespace {

constexpr float kPi = 3.14159265f;

ImVec2 floored(ImVec2 p) { return ImVec2(std::floor(p.x), std::floor(p.y)); }  // as ImGui sees a mouse position
float distance(ImVec2 a, ImVec2 b) { return std::hypot(a.x - b.x, a.y - b.y); }
// Counter-clockwise as seen on screen (y down), as the gizmo measures it.
float screen_angle(ImVec2 p, ImVec2 o) { return std::atan2(-(p.y - o.y), p.x - o.x); }
float wrapped(float a) { return std::remainder(a, 2 * kPi); }
glm::vec3 center(const Quad& q) { return (q.corners[0] + q.corners[1] + q.corners[2] + q.corners[3]) * 0.25f; }
glm::vec3 edge_x(const Quad& q) { return q.corners[2] - q.corners[0]; }
glm::vec3 edge_y(const Quad& q) { return q.corners[1] - q.corners[0]; }

void expect_near(glm::vec3 a, glm::vec3 b, float tol, const char* what) {
  EXPECT_NEAR(a.x, b.x, tol) << what;
  EXPECT_NEAR(a.y, b.y, tol) << what;
  EXPECT_NEAR(a.z, b.z, tol) << what;
}

class UiGizmoTest : public test::UiTest {
 protected:
  // A new quad facing the camera, selected and committed as an undo step of its own.
  int add_selected_quad() {
    const int q = add_quad(doc_.scene);
    doc_.selection = {SelectionKind::quad, q};
    frame();
    return q;
  }
  GizmoHandles gizmo(GizmoMode mode) { return make_gizmo(doc_, mode, state_.viewport.pos, state_.viewport.size); }
  // Presses at `from`, moves through `path` one frame a point, releases at its end.
  void drag(ImVec2 from, const std::vector<ImVec2>& path) {
    mouse_to(from);
    frame();
    mouse_button(true);
    frame();
    for (ImVec2 p : path) {
      mouse_to(p);
      frame();
      EXPECT_TRUE(state_.tools.interacting);
      EXPECT_GE(state_.tools.gizmo_handle, 0);
    }
    mouse_button(false);
    frame();
    EXPECT_EQ(state_.tools.gizmo_handle, -1);
  }
  // The point of `ring` farthest from the other rings (a grab that cannot be mistaken).
  ImVec2 clear_point(const GizmoHandles& g, int ring) {
    ImVec2 best{0, 0};
    float best_d = -1;
    for (ImVec2 p : g.rings[ring]) {
      float d = 1e30f;
      for (int other = 0; other < 3; ++other)
        if (other != ring)
          for (ImVec2 o : g.rings[other]) d = std::min(d, distance(p, o));
      if (d > best_d) {
        best_d = d;
        best = p;
      }
    }
    return floored(best);
  }
};

TEST_F(UiGizmoTest, RKeyThenARingDragTurnsTheQuadAboutItsCentreAsOneUndoStep) {
  const int qi = add_selected_quad();
  press(GLFW_KEY_R);
  EXPECT_EQ(state_.tools.gizmo_mode, GizmoMode::rotate);
  const Quad q0 = doc_.scene.quads[qi];
  const GizmoHandles g = gizmo(GizmoMode::rotate);
  ASSERT_TRUE(g.visible);
  ASSERT_TRUE(g.has_axis[2]);
  // The camera looks along -z: the z ring faces it, a counter-clockwise turn on screen is a
  // right-handed turn about +z.
  ASSERT_GT(glm::dot(glm::vec3(0, 0, 1), doc_.scene.camera.position - center(q0)), 0);
  const ImVec2 grab = clear_point(g, 2);
  mouse_to(grab);
  frame();
  ASSERT_EQ(state_.tools.gizmo_hover, 2);
  // A quarter turn counter-clockwise about the gizmo's centre, in six steps.
  const float radius = distance(grab, g.origin), a0 = screen_angle(grab, g.origin);
  std::vector<ImVec2> path;
  for (int i = 1; i <= 6; ++i) {
    const float a = a0 + 0.5f * kPi * float(i) / 6;
    path.push_back(floored(ImVec2(g.origin.x + radius * std::cos(a), g.origin.y - radius * std::sin(a))));
  }
  drag(grab, path);
  const Quad q1 = doc_.scene.quads[qi];
  const float turned = wrapped(screen_angle(path.back(), g.origin) - a0);
  EXPECT_NEAR(turned, 0.5f * kPi, 0.05f);  // the path's rounding to whole pixels
  const float size = glm::length(edge_x(q0));
  for (int c = 0; c < 4; ++c)
    expect_near(q1.corners[c], rotate_quad(q0, {0, 0, 1}, turned).corners[c], 1e-4f * size, "corner");
  expect_near(center(q1), center(q0), 1e-5f * size, "centre");
  EXPECT_NEAR(glm::length(edge_x(q1)), glm::length(edge_x(q0)), 1e-5f * size);
  EXPECT_NEAR(glm::length(edge_y(q1)), glm::length(edge_y(q0)), 1e-5f * size);
  // On screen the quad's corner went round with the mouse (the view is a little oblique).
  auto corner_angle = [&](const Quad& q) { return screen_angle(screen(q.corners[0]), screen(center(q))); };
  EXPECT_NEAR(wrapped(corner_angle(q1) - corner_angle(q0)), turned, 5 * kPi / 180);
  // The Properties panel's fields read the same quad: same size, turned about z.
  EXPECT_NEAR(quad_placement(q1).size.x, quad_placement(q0).size.x, 1e-5f * size);
  press(GLFW_KEY_Z, /*ctrl=*/true);  // the whole drag is one step
  EXPECT_EQ(doc_.scene.quads[qi], q0);
  EXPECT_EQ(doc_.selection, (Selection{SelectionKind::quad, qi}));
}

TEST_F(UiGizmoTest, ScaleButtonThenASquareDragStretchesOneEdgeAndTheCircleBoth) {
  const int qi = add_selected_quad();
  // The toolbar's Scale button, at the viewport's top left (found by hovering along its row).
  const float row_y = state_.viewport.pos.y + 6 + ImGui::GetFrameHeight() / 2;
  ImVec2 button(-1, -1);
  for (float x = state_.viewport.pos.x + 2; x < state_.viewport.pos.x + 240 && button.x < 0; x += 4) {
    mouse_to(ImVec2(x, row_y));
    frame();
    const ImGuiContext& g = *ImGui::GetCurrentContext();
    if (g.HoveredWindow && g.HoveredId != 0 && g.HoveredId == g.HoveredWindow->GetID("Scale")) button = ImVec2(x, row_y);
  }
  ASSERT_GE(button.x, 0) << "no Scale button in the viewport";
  EXPECT_TRUE(ImGui::FindWindowByName("##Tooltip_00") && ImGui::FindWindowByName("##Tooltip_00")->Active)
      << "no tooltip on the Scale button";
  click(button);
  EXPECT_EQ(state_.tools.gizmo_mode, GizmoMode::scale);
  EXPECT_EQ(doc_.selection, (Selection{SelectionKind::quad, qi}));  // the click was the button's

  // The x edge's square: drag it out by half the arrow's screen length.
  const Quad q0 = doc_.scene.quads[qi];
  GizmoHandles g = gizmo(GizmoMode::scale);
  ASSERT_TRUE(g.has_axis[0] && g.has_axis[1]);
  ASSERT_FALSE(g.has_axis[2]);  // a flat quad has no third edge
  const ImVec2 s(g.ends[0].x - g.origin.x, g.ends[0].y - g.origin.y);
  const ImVec2 grab = floored(ImVec2(g.origin.x + 0.9f * s.x, g.origin.y + 0.9f * s.y));
  mouse_to(grab);
  frame();
  ASSERT_EQ(state_.tools.gizmo_hover, 0);
  std::vector<ImVec2> path;
  for (int i = 1; i <= 5; ++i) path.push_back(floored(ImVec2(grab.x + 0.1f * s.x * i, grab.y + 0.1f * s.y * i)));
  drag(grab, path);
  const Quad q1 = doc_.scene.quads[qi];
  // Dragging by the arrow's own length would double the edge: half of it is 1.5 times.
  const float factor = 1 + ((path.back().x - grab.x) * s.x + (path.back().y - grab.y) * s.y) / (s.x * s.x + s.y * s.y);
  EXPECT_NEAR(factor, 1.5f, 0.05f);
  const float size = glm::length(edge_x(q0));
  expect_near(edge_x(q1), edge_x(q0) * factor, 1e-4f * size, "x edge");
  expect_near(edge_y(q1), edge_y(q0), 1e-4f * size, "y edge");
  expect_near(center(q1), center(q0), 1e-5f * size, "centre");
  EXPECT_NEAR(quad_placement(q1).size.x, quad_placement(q0).size.x * factor, 1e-4f * size);  // the Size field
  press(GLFW_KEY_Z, /*ctrl=*/true);
  EXPECT_EQ(doc_.scene.quads[qi], q0);

  // The circle: the mouse's distance from the centre 1.25 times, so both edges.
  g = gizmo(GizmoMode::scale);
  ASSERT_GT(g.uniform_radius, 0);
  const float diag = g.uniform_radius / std::sqrt(2.0f);
  const ImVec2 on_circle = floored(ImVec2(g.origin.x + diag, g.origin.y - diag));
  mouse_to(on_circle);
  frame();
  ASSERT_EQ(state_.tools.gizmo_hover, kUniformScaleHandle);
  const ImVec2 out = floored(ImVec2(g.origin.x + 1.25f * diag, g.origin.y - 1.25f * diag));
  drag(on_circle, {floored(ImVec2(g.origin.x + 1.1f * diag, g.origin.y - 1.1f * diag)), out});
  const float ratio = distance(out, g.origin) / distance(on_circle, g.origin);
  EXPECT_NEAR(ratio, 1.25f, 0.05f);
  const Quad q2 = doc_.scene.quads[qi];
  expect_near(edge_x(q2), edge_x(q0) * ratio, 1e-4f * size, "x edge");
  expect_near(edge_y(q2), edge_y(q0) * ratio, 1e-4f * size, "y edge");
  expect_near(center(q2), center(q0), 1e-5f * size, "centre");
  press(GLFW_KEY_Z, /*ctrl=*/true);
  EXPECT_EQ(doc_.scene.quads[qi], q0);
}

TEST_F(UiGizmoTest, TKeyThenTheCircleScalesASpheresRadius) {
  const int ball = visible_sphere();
  ASSERT_GE(ball, 0);
  doc_.selection = {SelectionKind::sphere, ball};
  press(GLFW_KEY_T);
  EXPECT_EQ(state_.tools.gizmo_mode, GizmoMode::scale);
  const Sphere s0 = doc_.scene.spheres[ball];
  const GizmoHandles g = gizmo(GizmoMode::scale);
  ASSERT_TRUE(g.visible);
  EXPECT_FALSE(g.has_axis[0] || g.has_axis[1] || g.has_axis[2]);  // a sphere has only the circle
  ASSERT_GT(g.uniform_radius, 0);
  const ImVec2 on_circle = floored(ImVec2(g.origin.x - g.uniform_radius, g.origin.y));
  mouse_to(on_circle);
  frame();
  ASSERT_EQ(state_.tools.gizmo_hover, kUniformScaleHandle);
  const ImVec2 in = floored(ImVec2(g.origin.x - 0.6f * g.uniform_radius, g.origin.y));
  drag(on_circle, {in});
  const float ratio = distance(in, g.origin) / distance(on_circle, g.origin);
  EXPECT_NEAR(doc_.scene.spheres[ball].radius, s0.radius * ratio, 1e-5f * s0.radius);
  EXPECT_EQ(doc_.scene.spheres[ball].center, s0.center);
  press(GLFW_KEY_Z, /*ctrl=*/true);
  EXPECT_EQ(doc_.scene.spheres[ball], s0);
  // A sphere has no rotation: the rotate mode shows no rings for it.
  press(GLFW_KEY_R);
  const GizmoHandles r = gizmo(GizmoMode::rotate);
  EXPECT_TRUE(r.rings[0].empty() && r.rings[1].empty() && r.rings[2].empty());
  press(GLFW_KEY_G);
  EXPECT_EQ(state_.tools.gizmo_mode, GizmoMode::move);
}

}  // namespace
}  // namespace glint
