// Where new and duplicated objects go (see object_placement.h).
#include "editor/object_placement.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace glint {
namespace {

float distance_to_segment(glm::vec3 p, glm::vec3 a, glm::vec3 b) {
  const glm::vec3 ab = b - a;
  const float len2 = glm::dot(ab, ab);
  const float t = len2 > 0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
  return glm::length(p - (a + t * ab));
}

// The index (0, 1, 2) of v's largest component in magnitude, skipping `skip`.
int dominant_axis(glm::vec3 v, int skip = -1) {
  int best = skip == 0 ? 1 : 0;
  for (int k = 0; k < 3; ++k)
    if (k != skip && std::abs(v[k]) > std::abs(v[best])) best = k;
  return best;
}

glm::vec3 axis(int k, float sign) {
  glm::vec3 a(0);
  a[k] = sign < 0 ? -1.0f : 1.0f;
  return a;
}

}  // namespace

float distance_to_quad(const Quad& q, glm::vec3 p) {
  const glm::vec3 o = q.corners[0], ex = q.corners[2] - o, ey = q.corners[1] - o;
  const float xx = glm::dot(ex, ex), xy = glm::dot(ex, ey), yy = glm::dot(ey, ey);
  const float det = xx * yy - xy * xy;
  if (det > 1e-12f * xx * yy) {
    // The point's coordinates along the edges: inside the parallelogram, the plane is nearest.
    const glm::vec3 d = p - o;
    const float dx = glm::dot(d, ex), dy = glm::dot(d, ey);
    const float a = (dx * yy - dy * xy) / det, b = (dy * xx - dx * xy) / det;
    if (a >= 0 && a <= 1 && b >= 0 && b <= 1) return glm::length(d - a * ex - b * ey);
  }
  const glm::vec3 p3 = o + ex + ey;
  return std::min({distance_to_segment(p, o, o + ex), distance_to_segment(p, o, o + ey),
                   distance_to_segment(p, o + ex, p3), distance_to_segment(p, o + ey, p3)});
}

bool touches_scene(const Scene& scene, glm::vec3 center, float radius) {
  for (const Sphere& s : scene.spheres)
    if (glm::length(s.center - center) < s.radius + radius) return true;
  for (const Quad& q : scene.quads)
    if (distance_to_quad(q, center) < radius) return true;
  return false;
}

glm::vec3 free_sphere_center(const Scene& scene, glm::vec3 preferred, float radius, glm::vec3 right, glm::vec3 up) {
  if (!touches_scene(scene, preferred, radius)) return preferred;
  constexpr int kReach = 6;
  std::vector<glm::ivec2> steps;
  for (int j = -kReach; j <= kReach; ++j)
    for (int i = -kReach; i <= kReach; ++i)
      if (i != 0 || j != 0) steps.push_back({i, j});
  // Nearest first; among equals, up before down and right before left (stable, so the same
  // scene always gives the same place).
  std::stable_sort(steps.begin(), steps.end(), [](glm::ivec2 a, glm::ivec2 b) {
    const int da = a.x * a.x + a.y * a.y, db = b.x * b.x + b.y * b.y;
    if (da != db) return da < db;
    if (a.y != b.y) return a.y > b.y;
    return a.x > b.x;
  });
  const float step = 2.5f * radius;
  for (glm::ivec2 s : steps) {
    const glm::vec3 c = preferred + right * (step * float(s.x)) + up * (step * float(s.y));
    if (!touches_scene(scene, c, radius)) return c;
  }
  return preferred;
}

AxisFrame nearest_axis_frame(glm::vec3 forward, glm::vec3 up) {
  const int f = dominant_axis(forward);
  const int u = dominant_axis(up, f);
  AxisFrame out;
  out.forward = axis(f, forward[f]);
  // An up along the forward axis (looking straight down with up = forward, say) has nothing
  // left over: any other axis is as near.
  out.up = axis(u, up[u] == 0 ? 1.0f : up[u]);
  out.right = glm::cross(out.forward, out.up);
  return out;
}

}  // namespace glint
