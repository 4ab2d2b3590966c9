// Picking through the shared intersection code, and click-to-focus.
#include "editor/picking.h"

#include <gtest/gtest.h>

#include "editor_test_util.h"

namespace glint {
namespace {

// Camera at z = 5 looking down -z, nothing in the scene yet.
Scene empty_scene() {
  Scene s;
  s.camera.position = {0, 0, 5};
  s.camera.target = {0, 0, 0};
  s.camera.up = {0, 1, 0};
  s.materials.push_back({.name = "m"});
  return s;
}

TEST(Picking, RayThroughCentrePicksSphere) {
  Scene s = empty_scene();
  s.spheres.push_back({"ball", {0, 0, 0}, 1, "m"});
  const auto hit = pick(s, {0.5f, 0.5f}, 16.0f / 9.0f);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->what, (Selection{SelectionKind::sphere, 0}));
  EXPECT_NEAR(hit->t, 4, 1e-5);
  EXPECT_NEAR(glm::length(hit->point - glm::vec3(0, 0, 1)), 0, 1e-5);
}

TEST(Picking, NearestOfTwoWins) {
  Scene s = empty_scene();
  s.spheres.push_back({"far", {0, 0, -3}, 1, "m"});
  s.spheres.push_back({"near", {0, 0, 0}, 1, "m"});
  auto hit = pick(s, {0.5f, 0.5f}, 1);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->what.index, 1);
  // Order does not matter.
  std::swap(s.spheres[0], s.spheres[1]);
  hit = pick(s, {0.5f, 0.5f}, 1);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->what.index, 0);
}

TEST(Picking, MissReturnsNothing) {
  Scene s = empty_scene();
  EXPECT_FALSE(pick(s, {0.5f, 0.5f}, 1));
  s.spheres.push_back({"ball", {0, 0, 0}, 1, "m"});
  EXPECT_FALSE(pick(s, {0.02f, 0.02f}, 1));  // top-left corner of the view passes beside it
  // Behind the camera is not a hit.
  s.spheres[0].center = {0, 0, 10};
  EXPECT_FALSE(pick(s, {0.5f, 0.5f}, 1));
}

TEST(Picking, FilmOriginIsTopLeft) {
  Scene s = empty_scene();
  s.spheres.push_back({"upper", {0, 1.2f, 0}, 0.5f, "m"});
  s.spheres.push_back({"lower", {0, -1.2f, 0}, 0.5f, "m"});
  // tan(20 deg) * 5 = 1.82 half-height at the target: y = 1.2 is at film y = 0.5 - 0.33 = 0.17.
  auto hit = pick(s, {0.5f, 0.17f}, 1);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->what.index, 0);
  hit = pick(s, {0.5f, 0.83f}, 1);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->what.index, 1);
}

TEST(Picking, QuadsFromBothSidesAndNearestAgainstSpheres) {
  Scene s = empty_scene();
  Quad q;
  q.name = "wall";
  q.material = "m";
  q.corners = {glm::vec3(-1, -1, 1), glm::vec3(-1, 1, 1), glm::vec3(1, -1, 1), glm::vec3(1, 1, 1)};
  s.quads.push_back(q);
  s.spheres.push_back({"behind", {0, 0, -1}, 0.5f, "m"});
  auto hit = pick(s, {0.5f, 0.5f}, 1);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->what, (Selection{SelectionKind::quad, 0}));
  EXPECT_NEAR(hit->t, 4, 1e-5);
  // Reversed winding (the back side) still hits.
  std::swap(s.quads[0].corners[1], s.quads[0].corners[2]);
  hit = pick(s, {0.5f, 0.5f}, 1);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->what.kind, SelectionKind::quad);
  // Moved behind the sphere: the sphere is nearer.
  for (glm::vec3& p : s.quads[0].corners) p.z = -3;
  hit = pick(s, {0.5f, 0.5f}, 1);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->what, (Selection{SelectionKind::sphere, 0}));
  // Beside the sphere the quad shows.
  hit = pick(s, {0.65f, 0.5f}, 1);  // 0.109 rad off axis: beside the ball (0.083 rad wide)
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->what.kind, SelectionKind::quad);
}

TEST(Picking, HitsThroughTheQuadDiagonal) {
  Scene s = empty_scene();
  Quad q;
  q.name = "wall";
  q.material = "m";
  q.corners = {glm::vec3(-1, -1, 0), glm::vec3(-1, 1, 0), glm::vec3(1, -1, 0), glm::vec3(1, 1, 0)};
  s.quads.push_back(q);
  // The diagonal p1-p2 runs through the centre; sample along it.
  int hits = 0;
  for (int k = 0; k <= 20; ++k) {
    const float f = 0.45f + 0.1f * static_cast<float>(k) / 20;
    hits += pick(s, {f, f}, 1).has_value();
  }
  EXPECT_EQ(hits, 21);
}

TEST(ClickToFocus, DistanceAlongViewDirection) {
  Camera c;
  c.position = {0, 0, 5};
  c.target = {0, 0, 0};
  EXPECT_NEAR(focus_distance_for(c, {1, 0, 0}), 5, 1e-6);  // not the Euclidean 5.099
  EXPECT_NEAR(focus_distance_for(c, {0, 3, -2}), 7, 1e-6);
  c.focus_distance = 2;
  EXPECT_EQ(focus_distance_for(c, {0, 0, 9}), 2);  // behind the camera: unchanged
}

TEST(ClickToFocus, PickThenFocusMakesHitSharp) {
  Scene s = empty_scene();
  s.camera.target = {0, 0, -1};
  s.spheres.push_back({"ball", {1, 0, 0}, 0.5f, "m"});
  // The ray through (1, 0, 0): slope 1/5, i.e. film x = 0.5 + 0.1 / tan(20 deg).
  const auto hit = pick(s, {0.5f + 0.1f / std::tan(glm::radians(20.0f)), 0.5f}, 1);
  ASSERT_TRUE(hit);
  s.camera.focus_distance = focus_distance_for(s.camera, hit->point);
  EXPECT_NEAR(s.camera.focus_distance, 5 - hit->point.z, 1e-5);
  EXPECT_LT(s.camera.focus_distance, 4.6f);  // the front of the ball, nearer than its centre
  EXPECT_EQ(test::problems(s), "");
}

}  // namespace
}  // namespace glint
