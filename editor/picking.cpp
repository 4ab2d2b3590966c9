// Picking with the shared intersection code: the editor selects exactly what the renderer
// draws (same quad diagonal handling, same sphere robustness).
#include "editor/picking.h"

#include <cmath>

#include "renderer/camera_frame.h"
#include "renderer/shader_lib.h"

namespace glint {

std::optional<PickHit> pick(const Scene& scene, glm::vec2 film, float aspect) {
  if (!(aspect > 0) || !std::isfinite(aspect)) return std::nullopt;
  const gpu::Ray ray = camera_center_ray(scene.camera, aspect, film);
  const glm::vec3 d = ray.direction;
  if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z)) return std::nullopt;

  // Each test only accepts hits nearer than the best so far (tmax), so the nearest wins.
  float best = INFINITY;
  Selection what;
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& s = scene.spheres[i];
    const float t = gpu::intersect_sphere(ray, s.center, s.radius, 0.0f, best);
    if (t != gpu::NO_HIT) {
      best = t;
      what = {SelectionKind::sphere, static_cast<int>(i)};
    }
  }
  for (size_t i = 0; i < scene.quads.size(); ++i) {
    const Quad& q = scene.quads[i];
    const gpu::QuadHit h =
        gpu::intersect_quad(ray, q.corners[0], q.corners[1], q.corners[2], q.corners[3], q.uvs[0],
                            q.uvs[1], q.uvs[2], q.uvs[3], 0.0f, best);
    if (h.t != gpu::NO_HIT) {
      best = h.t;
      what = {SelectionKind::quad, static_cast<int>(i)};
    }
  }
  if (what.kind == SelectionKind::none) return std::nullopt;
  return PickHit{what, best, ray.origin + best * ray.direction};
}

float focus_distance_for(const Camera& camera, glm::vec3 point) {
  const glm::vec3 view = camera.target - camera.position;
  const float length = glm::length(view);
  if (!(length > 0)) return camera.focus_distance;
  // Depth along the view direction (what the thin lens focuses), not the distance to the point.
  const float depth = glm::dot(point - camera.position, view / length);
  // A point behind the camera has no sharp plane; keep a valid (positive) distance.
  return std::isfinite(depth) && depth > 0 ? depth : camera.focus_distance;
}

}  // namespace glint
