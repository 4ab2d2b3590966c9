// Camera navigation (see camera_control.h). Every function keeps the camera valid for
// validate_scene: position != target, up not parallel to the view, finite values.
#include "editor/camera_control.h"

#include <algorithm>
#include <cmath>

namespace glint {
namespace {

// Orbit stops this far (radians) from the poles, so the view never becomes parallel to up
// (validate_scene rejects |sin| <= 1e-6) and the turntable never flips over.
constexpr float kPoleMargin = 0.01f;

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

glm::vec3 unit_up(const Camera& c) {
  const float l = glm::length(c.up);
  return l > 0 && finite(c.up) ? c.up / l : glm::vec3(0, 1, 0);
}

// Any unit vector perpendicular to n.
glm::vec3 perpendicular(glm::vec3 n) {
  return glm::normalize(glm::cross(n, std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
}

struct Frame {
  glm::vec3 forward, right, up;
  float distance;
};

Frame frame_of(const Camera& c) {
  glm::vec3 v = c.target - c.position;
  const float dist = glm::length(v);
  const glm::vec3 f = dist > 0 ? v / dist : glm::vec3(0, 0, -1);
  glm::vec3 r = glm::cross(f, unit_up(c));
  r = glm::length(r) > 1e-6f ? glm::normalize(r) : perpendicular(f);
  return {f, r, glm::cross(r, f), dist};
}

// The smallest distance kept between position and target: a few float steps at the target's
// magnitude, so that position never rounds onto it.
float min_distance(const Camera& c) {
  const float m = std::max({std::abs(c.target.x), std::abs(c.target.y), std::abs(c.target.z), 1.0f});
  return 1e-4f * m;
}

}  // namespace

void orbit(Camera& camera, float yaw, float pitch) {
  if (!std::isfinite(yaw) || !std::isfinite(pitch)) return;
  const glm::vec3 up = unit_up(camera);
  glm::vec3 offset = camera.position - camera.target;
  const float r = glm::length(offset);
  if (!(r > 0)) return;
  const glm::vec3 dir = offset / r;
  // Polar angle from up and the horizontal direction (in the plane perpendicular to up).
  const float theta = std::acos(std::clamp(glm::dot(dir, up), -1.0f, 1.0f));
  glm::vec3 h = dir - up * glm::dot(dir, up);
  h = glm::length(h) > 1e-6f ? glm::normalize(h) : perpendicular(up);
  // Yaw: rotate h about up (Rodrigues; h is perpendicular to up).
  const glm::vec3 side = glm::cross(up, h);
  h = glm::normalize(h * std::cos(yaw) + side * std::sin(yaw));
  // Pitch > 0 raises the camera (theta shrinks), clamped short of the poles.
  const float pi = 3.14159265358979f;
  const float new_theta = std::clamp(theta - pitch, kPoleMargin, pi - kPoleMargin);
  camera.position = camera.target + r * (up * std::cos(new_theta) + h * std::sin(new_theta));
  camera.up = up;
}

void pan(Camera& camera, glm::vec2 delta) {
  if (!std::isfinite(delta.x) || !std::isfinite(delta.y)) return;
  const Frame f = frame_of(camera);
  const float view_height = 2 * f.distance * std::tan(glm::radians(camera.vfov_deg) * 0.5f);
  const glm::vec3 move = (f.right * delta.x + f.up * delta.y) * view_height;
  if (!finite(move)) return;
  camera.position += move;
  camera.target += move;
}

void dolly(Camera& camera, float factor) {
  if (!(factor > 0) || !std::isfinite(factor)) return;
  const Frame f = frame_of(camera);
  const float dist = std::max(f.distance * factor, min_distance(camera));
  if (!std::isfinite(dist)) return;
  camera.position = camera.target - f.forward * dist;
}

void fly(Camera& camera, glm::vec3 move) {
  if (!finite(move)) return;
  const Frame f = frame_of(camera);
  const glm::vec3 delta = f.right * move.x + f.up * move.y + f.forward * move.z;
  camera.position += delta;
  camera.target += delta;
}

void frame(Camera& camera, glm::vec3 center, float radius) {
  if (!finite(center) || !std::isfinite(radius)) return;
  const Frame f = frame_of(camera);
  // The sphere's silhouette spans the vertical fov at distance r / sin(fov/2).
  const float half = glm::radians(std::clamp(camera.vfov_deg, 1.0f, 179.0f)) * 0.5f;
  const float r = radius > 0 ? radius : 1.0f;
  const float dist = std::max(r / std::sin(half), min_distance(camera));
  camera.target = center;
  camera.position = center - f.forward * dist;
  camera.focus_distance = dist;
}

}  // namespace glint
