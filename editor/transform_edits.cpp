// Rotation and scale about an object's centre (see transform_edits.h).
#include "editor/transform_edits.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>

namespace glint {
namespace {

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

glm::vec3 center_of(const Quad& q) { return (q.corners[0] + q.corners[1] + q.corners[2] + q.corners[3]) * 0.25f; }

glm::vec3 unit_or_zero(glm::vec3 v) {
  const float len = glm::length(v);
  return len > 0 && std::isfinite(len) ? v / len : glm::vec3(0);
}

}  // namespace

Quad rotate_quad(const Quad& quad, glm::vec3 axis, float radians) {
  const float len = glm::length(axis);
  if (!(len > 0) || !std::isfinite(len) || !std::isfinite(radians)) return quad;
  const glm::quat r = glm::angleAxis(radians, axis / len);
  const glm::vec3 c = center_of(quad);
  Quad out = quad;
  for (glm::vec3& p : out.corners) p = c + r * (p - c);
  return out;
}

Quad scale_quad(const Quad& quad, float scale_x, float scale_y) {
  if (!(scale_x > 0) || !(scale_y > 0) || !std::isfinite(scale_x) || !std::isfinite(scale_y)) return quad;
  const glm::vec3 c = center_of(quad);
  const glm::vec3 ex = quad.corners[2] - quad.corners[0], ey = quad.corners[1] - quad.corners[0];
  const glm::vec3 ux = unit_or_zero(ex), uy = unit_or_zero(ey);
  // Split each corner's offset from the centre into its parts along the edges (solving the 2x2
  // system of the edge directions, which need not be orthogonal) and the rest.
  const float xx = glm::dot(ux, ux), xy = glm::dot(ux, uy), yy = glm::dot(uy, uy);
  const float det = xx * yy - xy * xy;
  Quad out = quad;
  for (glm::vec3& p : out.corners) {
    const glm::vec3 d = p - c;
    float a = 0, b = 0;
    if (det > 1e-12f) {
      const float dx = glm::dot(d, ux), dy = glm::dot(d, uy);
      a = (dx * yy - dy * xy) / det;
      b = (dy * xx - dx * xy) / det;
    } else if (xx > 0) {
      a = glm::dot(d, ux);
    } else if (yy > 0) {
      b = glm::dot(d, uy);
    }
    const glm::vec3 rest = d - a * ux - b * uy;
    p = c + a * scale_x * ux + b * scale_y * uy + rest;
  }
  if (!finite(out.corners[0]) || !finite(out.corners[3])) return quad;
  return out;
}

glm::vec3 quad_edge_x(const Quad& quad) { return unit_or_zero(quad.corners[2] - quad.corners[0]); }
glm::vec3 quad_edge_y(const Quad& quad) { return unit_or_zero(quad.corners[1] - quad.corners[0]); }

float scaled_radius(float radius, float scale) {
  if (!(scale > 0) || !std::isfinite(scale)) return radius;
  const float r = radius * scale;
  return std::isfinite(r) ? std::max(r, kMinRadius) : radius;
}

}  // namespace glint
