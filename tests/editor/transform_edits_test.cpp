// Rotation and scale about an object's centre (the gizmo's maths): what must stay (centre, edge
// lengths, the angle between the edges, the plane) stays, and what must change changes as asked.
#include "editor/transform_edits.h"

#include <gtest/gtest.h>

#include <cmath>

#include "editor/scene_edits.h"

namespace glint {
namespace {

constexpr float kPi = 3.14159265f;

glm::vec3 center(const Quad& q) { return (q.corners[0] + q.corners[1] + q.corners[2] + q.corners[3]) * 0.25f; }
glm::vec3 edge_x(const Quad& q) { return q.corners[2] - q.corners[0]; }
glm::vec3 edge_y(const Quad& q) { return q.corners[1] - q.corners[0]; }

void expect_near(glm::vec3 a, glm::vec3 b, float tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// A tilted 2 x 0.5 rectangle away from the origin (so that "about the centre" matters).
Quad tilted_rectangle() {
  Quad q;
  set_quad_placement(q, QuadPlacement{{1.5f, -0.25f, 3}, {2, 0.5f}, {20, -35, 10}});
  return q;
}

TEST(TransformEdits, RotationKeepsCentreEdgeLengthsAndShape) {
  const Quad q = tilted_rectangle();
  for (glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), glm::vec3(1, 2, -0.5f)})
    for (float angle : {0.3f, -1.2f, 2.9f}) {
      const Quad r = rotate_quad(q, axis, angle);
      expect_near(center(r), center(q), 1e-5f);
      EXPECT_NEAR(glm::length(edge_x(r)), glm::length(edge_x(q)), 1e-5f);
      EXPECT_NEAR(glm::length(edge_y(r)), glm::length(edge_y(q)), 1e-5f);
      EXPECT_NEAR(glm::dot(edge_x(r), edge_y(r)), glm::dot(edge_x(q), edge_y(q)), 1e-5f);
      // Still a parallelogram: p3 = p1 + p2 - p0.
      expect_near(r.corners[3], r.corners[1] + r.corners[2] - r.corners[0], 1e-5f);
      // Components along the axis do not change; the perpendicular parts turn by the angle.
      const glm::vec3 a = glm::normalize(axis);
      EXPECT_NEAR(glm::dot(edge_x(r), a), glm::dot(edge_x(q), a), 1e-5f);
      const glm::vec3 before = edge_x(q) - a * glm::dot(edge_x(q), a);
      const glm::vec3 after = edge_x(r) - a * glm::dot(edge_x(r), a);
      const float turned = std::atan2(glm::dot(glm::cross(before, after), a), glm::dot(before, after));
      EXPECT_NEAR(turned, angle, 1e-4f) << "axis " << axis.x << " " << axis.y << " " << axis.z;
    }
}

TEST(TransformEdits, RotationIsRightHandedAboutTheWorldAxis) {
  // The x edge of an axis-aligned quad turned a quarter about +z points along +y.
  Quad q;
  q.corners = {glm::vec3(0, 0, 0), glm::vec3(0, 1, 0), glm::vec3(2, 0, 0), glm::vec3(2, 1, 0)};
  const Quad r = rotate_quad(q, {0, 0, 1}, kPi / 2);
  expect_near(edge_x(r), {0, 2, 0}, 1e-5f);
  expect_near(edge_y(r), {-1, 0, 0}, 1e-5f);
  expect_near(center(r), {1, 0.5f, 0}, 1e-6f);
  // The UI's placement fields see the same turn: the z Euler angle grows by 90 degrees.
  EXPECT_NEAR(quad_placement(r).rotation_deg.z, quad_placement(q).rotation_deg.z + 90, 1e-3f);
}

TEST(TransformEdits, RotationWithoutAValidAxisOrAngleChangesNothing) {
  const Quad q = tilted_rectangle();
  EXPECT_EQ(rotate_quad(q, {0, 0, 0}, 1), q);
  EXPECT_EQ(rotate_quad(q, {0, 1, 0}, std::nanf("")), q);
  EXPECT_EQ(rotate_quad(q, {INFINITY, 0, 0}, 1), q);
}

TEST(TransformEdits, ScaleMultipliesEachEdgeAboutTheCentre) {
  const Quad q = tilted_rectangle();
  const Quad s = scale_quad(q, 1.5f, 0.25f);
  expect_near(center(s), center(q), 1e-5f);
  expect_near(edge_x(s), edge_x(q) * 1.5f, 1e-5f);  // same direction, 1.5 times as long
  expect_near(edge_y(s), edge_y(q) * 0.25f, 1e-5f);
  expect_near(s.corners[3], s.corners[1] + s.corners[2] - s.corners[0], 1e-5f);
  // In the UI's placement: the size changes, the centre and the orientation stay.
  const QuadPlacement a = quad_placement(q), b = quad_placement(s);
  EXPECT_NEAR(b.size.x, a.size.x * 1.5f, 1e-5f);
  EXPECT_NEAR(b.size.y, a.size.y * 0.25f, 1e-5f);
  expect_near(b.rotation_deg, a.rotation_deg, 1e-3f);
  EXPECT_EQ(s.uvs, q.uvs);  // the texture stretches with it
}

TEST(TransformEdits, ScaleOfASkewedQuadKeepsItsShapeAndPlane) {
  // A parallelogram whose edges meet at 60 degrees: scaling x moves the corners along x only.
  Quad q;
  const glm::vec3 ex(2, 0, 0), ey(0.5f, std::sqrt(3.0f) * 0.5f, 0);
  q.corners = {glm::vec3(1, 1, 1), glm::vec3(1, 1, 1) + ey, glm::vec3(1, 1, 1) + ex, glm::vec3(1, 1, 1) + ex + ey};
  const Quad s = scale_quad(q, 2, 1);
  expect_near(edge_x(s), ex * 2.0f, 1e-5f);
  expect_near(edge_y(s), ey, 1e-5f);
  expect_near(center(s), center(q), 1e-5f);
  for (const glm::vec3& p : s.corners) EXPECT_NEAR(p.z, 1, 1e-6f);
}

TEST(TransformEdits, ScaleRefusesFactorsThatWouldDegenerate) {
  const Quad q = tilted_rectangle();
  EXPECT_EQ(scale_quad(q, 0, 1), q);
  EXPECT_EQ(scale_quad(q, 1, -2), q);
  EXPECT_EQ(scale_quad(q, std::nanf(""), 1), q);
  EXPECT_EQ(scale_quad(q, INFINITY, 1), q);
}

TEST(TransformEdits, EdgeDirectionsAreUnitVectorsAlongTheEdges) {
  const Quad q = tilted_rectangle();
  EXPECT_NEAR(glm::length(quad_edge_x(q)), 1, 1e-6f);
  expect_near(quad_edge_x(q) * glm::length(edge_x(q)), edge_x(q), 1e-5f);
  expect_near(quad_edge_y(q) * glm::length(edge_y(q)), edge_y(q), 1e-5f);
  Quad flat;  // all corners at the origin
  expect_near(quad_edge_x(flat), glm::vec3(0), 0);
}

TEST(TransformEdits, SphereRadiusScalesAndStaysPositive) {
  EXPECT_FLOAT_EQ(scaled_radius(0.5f, 3), 1.5f);
  EXPECT_FLOAT_EQ(scaled_radius(0.5f, 1e-9f), kMinRadius);
  EXPECT_FLOAT_EQ(scaled_radius(0.5f, 0), 0.5f);
  EXPECT_FLOAT_EQ(scaled_radius(0.5f, -1), 0.5f);
  EXPECT_FLOAT_EQ(scaled_radius(0.5f, std::nanf("")), 0.5f);
}

}  // namespace
}  // namespace glint
