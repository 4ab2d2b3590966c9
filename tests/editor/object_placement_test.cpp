// Where new and duplicated objects go (editor/object_placement.h, scene_edits.h), and the
// properties panel's remembered forms of rotations and emissions (editor/shown_values.h).
#include "editor/object_placement.h"

#include <gtest/gtest.h>

#include <cmath>

#include "editor/scene_edits.h"
#include "editor/shown_values.h"
#include "editor/transform_edits.h"
#include "editor_test_util.h"
#include "renderer/project_file.h"

namespace glint {
namespace {

using test::problems;

const std::filesystem::path kProjects = std::filesystem::path(GLINT_SOURCE_DIR) / "projects";

// A new sphere touches no sphere or quad, in a new scene (whose focus is on its sphere) and in
// the examples, and shows in front of the camera.
TEST(ObjectPlacement, NewSpheresLandClearOfEverything) {
  std::vector<Scene> scenes{new_scene()};
  for (const char* name : {"default", "cornell_box", "textured_spheres", "roughness_ladder"})
    scenes.push_back(load_project(kProjects / (std::string(name) + ".glint")));
  for (Scene& s : scenes) {
    for (int n = 0; n < 3; ++n) {  // and the next ones clear of the first
      const Scene before = s;
      const Sphere& added = s.spheres[static_cast<size_t>(add_sphere(s))];
      EXPECT_FALSE(touches_scene(before, added.center, added.radius)) << s.base_dir << " sphere " << n;
      const Camera& c = s.camera;
      EXPECT_GT(glm::dot(added.center - c.position, glm::normalize(c.target - c.position)), 0);
    }
    EXPECT_EQ(problems(s), "");
  }
}

TEST(ObjectPlacement, DistanceToAQuad) {
  Quad q;
  q.corners = {glm::vec3{0, 0, 0}, glm::vec3{0, 2, 0}, glm::vec3{4, 0, 0}, glm::vec3{4, 2, 0}};
  EXPECT_FLOAT_EQ(distance_to_quad(q, {1, 1, 3}), 3);   // over its face
  EXPECT_FLOAT_EQ(distance_to_quad(q, {6, 1, 0}), 2);   // beside an edge, in its plane
  EXPECT_FLOAT_EQ(distance_to_quad(q, {7, 6, 0}), 5);   // beyond a corner (3, 4, 0)
  EXPECT_FLOAT_EQ(distance_to_quad(q, {2, -1, -1}), std::sqrt(2.0f));
}

// Duplicates sit beside the original at a distance that grows with its size, never on it.
TEST(ObjectPlacement, DuplicatesAreOffsetByTheirSize) {
  for (float radius : {0.05f, 0.5f, 3.0f}) {
    Scene s = new_scene();
    s.spheres[0].radius = radius;
    const Sphere copy = s.spheres[static_cast<size_t>(duplicate(s, {SelectionKind::sphere, 0}))];
    const float gap = glm::length(copy.center - s.spheres[0].center);
    EXPECT_GE(gap, 2 * radius) << radius;  // clear of it
    EXPECT_LE(gap, 3 * radius) << radius;  // and right beside it
  }
  for (float half : {0.1f, 4.0f}) {
    Scene s = new_scene();
    // A wall facing the camera, 2 * half wide.
    s.quads[0].corners = {glm::vec3{-half, half, 0}, glm::vec3{-half, -half, 0}, glm::vec3{half, half, 0},
                          glm::vec3{half, -half, 0}};
    const Quad copy = s.quads[static_cast<size_t>(duplicate(s, {SelectionKind::quad, 0}))];
    const float shift = copy.corners[0].x - s.quads[0].corners[0].x;
    EXPECT_GE(shift, 2 * half) << half;
    EXPECT_LE(shift, 3 * half) << half;
  }
}

// A new quad faces the camera at whole quarter turns, however the camera is tilted.
TEST(ObjectPlacement, NewQuadsStartAtRightAngles) {
  Scene s = load_project(kProjects / "default.glint");
  for (glm::vec3 from : {glm::vec3{0.3f, 1.7f, 5}, glm::vec3{4, 0.8f, -1}, glm::vec3{0.2f, 6, 0.5f}}) {
    s.camera.position = s.camera.target + from;
    const Quad& q = s.quads[static_cast<size_t>(add_quad(s))];
    const glm::vec3 r = quad_placement(q).rotation_deg;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(std::remainder(r[k], 90.0f), 0, 1e-3) << r[k];
    const glm::vec3 normal = glm::cross(q.corners[1] - q.corners[0], q.corners[2] - q.corners[0]);
    EXPECT_GT(glm::dot(normal, s.camera.position - (q.corners[0] + q.corners[3]) * 0.5f), 0);
  }
  EXPECT_EQ(problems(s), "");
}

// The panel keeps the Euler angles it was given while the quad is as they made it; after the
// gizmo turned it, it shows the angles nearest to those, not a far equivalent.
TEST(ShownValues, EulerAnglesStayAsTypedAndFollowTheGizmo) {
  Quad q;
  QuadPlacement p;
  p.size = {1, 1};
  p.rotation_deg = {180, 100, 0};
  set_quad_placement(q, p);
  EXPECT_GT(glm::length(quad_placement(q).rotation_deg - p.rotation_deg), 1);  // another triple
  QuadRotationView view;
  remember_rotation(view, 3, q, p.rotation_deg);
  EXPECT_EQ(shown_rotation(view, 3, q), p.rotation_deg);
  // The world Y ring: Ry(5) Rx(180) Ry(100) = Rx(180) Ry(95).
  q = rotate_quad(q, {0, 1, 0}, glm::radians(5.0f));
  const glm::vec3 turned = shown_rotation(view, 3, q);
  EXPECT_NEAR(turned.x, 180, 1e-3);
  EXPECT_NEAR(turned.y, 95, 1e-3);
  EXPECT_NEAR(turned.z, 0, 1e-3);
  // Another quad: its own angles, in -180..180.
  Quad other;
  p.rotation_deg = {0, 30, 0};
  set_quad_placement(other, p);
  EXPECT_NEAR(shown_rotation(view, 4, other).y, 30, 1e-3);
}

TEST(ShownValues, EulerAnglesNearAGivenTriple) {
  for (glm::vec3 deg : {glm::vec3{10, 20, 30}, glm::vec3{170, 120, -60}, glm::vec3{-90, 90, 45}, glm::vec3{300, -30, 10}}) {
    Quad q;
    QuadPlacement p;
    p.rotation_deg = deg;
    set_quad_placement(q, p);
    const glm::vec3 back = euler_xyz_near(quad_frame(q), deg);
    EXPECT_NEAR(glm::length(back - deg), 0, 0.02f) << deg.x << " " << deg.y << " " << deg.z;
  }
}

// Emission as colour (0..1) x strength: none shows as white at 0; a colour chosen at 0 stays;
// a bright emission splits into its hue and its brightest channel.
TEST(ShownValues, EmissionIsColourTimesStrength) {
  EmissionView view;
  EmissionForm f = shown_emission(view, 0, glm::vec3(0));
  EXPECT_EQ(f.colour, glm::vec3(1));
  EXPECT_EQ(f.strength, 0);
  const glm::vec3 none = set_emission(view, 0, {{1, 0.5f, 0}, 0});
  EXPECT_EQ(none, glm::vec3(0));
  EXPECT_EQ(shown_emission(view, 0, none).colour, glm::vec3(1, 0.5f, 0));
  const glm::vec3 lit = set_emission(view, 0, {{1, 0.5f, 0}, 20});
  EXPECT_EQ(lit, glm::vec3(20, 10, 0));
  f = shown_emission(EmissionView{}, 0, glm::vec3(8, 4, 2));  // from the file
  EXPECT_EQ(f.colour, glm::vec3(1, 0.5f, 0.25f));
  EXPECT_EQ(f.strength, 8);
  EXPECT_EQ(set_emission(view, 0, {{2, -1, 0.5f}, -3}), glm::vec3(0));  // clamped
  EXPECT_EQ(set_emission(view, 0, {{2, -1, 0.5f}, 2}), glm::vec3(2, 0, 1));
}

}  // namespace
}  // namespace glint
