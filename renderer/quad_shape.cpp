#include "renderer/quad_shape.h"

#include <algorithm>
#include <cmath>

namespace glint {

bool quad_is_planar_convex(const std::array<glm::vec3, 4>& corners) {
  const glm::dvec3 p0(corners[0]), p1(corners[1]), p2(corners[2]), p3(corners[3]);
  const glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
  const double area2 = glm::length(n);
  if (!(area2 > 0.0) || !std::isfinite(area2)) return false;
  double extent = 0.0;
  const glm::dvec3 p[4] = {p0, p1, p2, p3};
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) extent = std::max(extent, glm::length(p[i] - p[j]));
  if (std::abs(glm::dot(p3 - p0, n / area2)) > std::ldexp(extent, -23)) return false;
  const glm::dvec3 boundary[4] = {p0, p1, p3, p2};
  for (int i = 0; i < 4; ++i) {
    const glm::dvec3 in = boundary[i] - boundary[(i + 3) % 4];
    const glm::dvec3 out = boundary[(i + 1) % 4] - boundary[i];
    if (glm::dot(glm::cross(in, out), n) < 0.0) return false;
  }
  return true;
}

bool quad_is_parallelogram(const std::array<glm::vec3, 4>& corners) {
  const glm::dvec3 p0(corners[0]), p1(corners[1]), p2(corners[2]), p3(corners[3]);
  const double area2 = glm::length(glm::cross(p1 - p0, p2 - p0));
  if (!(area2 > 0.0) || !std::isfinite(area2)) return false;
  const double extent = std::max(glm::length(p3 - p0), glm::length(p2 - p1));  // the diagonals
  return glm::length(p3 - (p1 + p2 - p0)) <= std::ldexp(extent, -21);
}

}  // namespace glint
