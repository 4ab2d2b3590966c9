// Camera navigation invariants: valid cameras out, no flips at the poles, no dolly through the
// target, framing by the vertical field of view.
#include "editor/camera_control.h"

#include <cmath>

#include <gtest/gtest.h>

#include "editor_test_util.h"

namespace glint {
namespace {

Camera start() {
  Camera c;
  c.position = {0, 1, 5};
  c.target = {0, 0.5f, 0};
  c.up = {0, 1, 0};
  return c;
}

// What validate_scene requires of a camera.
bool valid(const Camera& c) {
  Scene s;
  s.camera = c;
  return validate_scene(s, false).empty();
}

float distance(const Camera& c) { return glm::length(c.position - c.target); }

TEST(CameraControl, OrbitKeepsDistanceAndTarget) {
  Camera c = start();
  const float d = distance(c);
  orbit(c, 0.7f, 0.3f);
  EXPECT_NEAR(distance(c), d, 1e-4);
  EXPECT_EQ(c.target, start().target);
  EXPECT_NE(c.position, start().position);
  EXPECT_TRUE(valid(c));
}

TEST(CameraControl, OrbitYawIsAboutUp) {
  Camera c = start();
  orbit(c, glm::radians(90.0f), 0);
  EXPECT_NEAR(c.position.y, 1, 1e-5);  // height unchanged
  EXPECT_NEAR(std::abs(c.position.x), 5, 1e-4);
  orbit(c, glm::radians(270.0f), 0);  // full circle
  EXPECT_NEAR(glm::length(c.position - start().position), 0, 1e-4);
}

TEST(CameraControl, OrbitStopsShortOfThePoles) {
  Camera c = start();
  for (int k = 0; k < 100; ++k) {
    orbit(c, 0.05f, 0.2f);  // keeps pitching up, far past the pole
    ASSERT_TRUE(valid(c)) << k;
    // Never over the top: the camera stays on the same side (above the target, not flipped).
    const glm::vec3 dir = glm::normalize(c.position - c.target);
    ASSERT_LT(dir.y, 1.0f);
    ASSERT_GT(dir.y, 0.0f);
  }
  const glm::vec3 dir = glm::normalize(c.position - c.target);
  EXPECT_GT(dir.y, 0.999f);  // it did reach (nearly) the pole
  // Pitching back down works from there (no stuck state).
  orbit(c, 0, -0.5f);
  EXPECT_LT(glm::normalize(c.position - c.target).y, 0.95f);
  for (int k = 0; k < 100; ++k) orbit(c, 0, -0.2f);
  EXPECT_TRUE(valid(c));
  EXPECT_LT(glm::normalize(c.position - c.target).y, -0.999f);
}

TEST(CameraControl, PanMovesPositionAndTargetTogether) {
  Camera c = start();
  const glm::vec3 view = c.target - c.position;
  pan(c, {0.5f, 0});
  EXPECT_EQ(c.target - c.position, view);
  // Half the view height at the target distance, to the right (+x for this camera).
  const float height = 2 * distance(start()) * std::tan(glm::radians(20.0f));
  EXPECT_NEAR(c.target.x, 0.5f * height, 1e-4);
  pan(c, {0, 1});
  EXPECT_GT(c.target.y, start().target.y);
  EXPECT_TRUE(valid(c));
}

TEST(CameraControl, DollyNeverReachesTarget) {
  Camera c = start();
  const float d = distance(c);
  dolly(c, 0.5f);
  EXPECT_NEAR(distance(c), d * 0.5f, 1e-4);
  EXPECT_EQ(c.target, start().target);
  for (int k = 0; k < 500; ++k) dolly(c, 0.1f);
  EXPECT_GT(distance(c), 0);
  EXPECT_NE(c.position, c.target);
  EXPECT_TRUE(valid(c));
  // Direction preserved: still looking the same way.
  const glm::vec3 f0 = glm::normalize(start().target - start().position);
  EXPECT_GT(glm::dot(glm::normalize(c.target - c.position), f0), 0.999f);
  dolly(c, 1e6f);
  EXPECT_GT(distance(c), 1);
  const Camera before = c;
  dolly(c, 0);  // nonsense factors are ignored
  dolly(c, -2);
  dolly(c, NAN);
  EXPECT_EQ(c, before);
}

TEST(CameraControl, FlyMovesInCameraFrame) {
  Camera c;
  c.position = {0, 0, 5};
  c.target = {0, 0, 0};
  fly(c, {0, 0, 1});  // forward is -z
  EXPECT_NEAR(c.position.z, 4, 1e-6);
  EXPECT_NEAR(c.target.z, -1, 1e-6);
  fly(c, {2, 0, 0});  // right is +x
  EXPECT_NEAR(c.position.x, 2, 1e-6);
  fly(c, {0, 3, 0});
  EXPECT_NEAR(c.position.y, 3, 1e-6);
  EXPECT_TRUE(valid(c));
}

TEST(CameraControl, FrameFitsSphereInVerticalFov) {
  Camera c = start();
  c.vfov_deg = 30;
  const glm::vec3 center{2, 1, -3};
  const float r = 0.75f;
  const glm::vec3 dir_before = glm::normalize(c.target - c.position);
  frame(c, center, r);
  EXPECT_EQ(c.target, center);
  const float d = distance(c);
  // The silhouette's half-angle is asin(r / d): exactly half the vertical fov.
  EXPECT_NEAR(glm::degrees(std::asin(r / d)), 15, 1e-3);
  EXPECT_NEAR(c.focus_distance, d, 1e-4);
  EXPECT_GT(glm::dot(glm::normalize(c.target - c.position), dir_before), 0.9999f);
  EXPECT_TRUE(valid(c));
}

}  // namespace
}  // namespace glint
