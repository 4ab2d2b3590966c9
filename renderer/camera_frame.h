// The camera of the scene model as the shader's CameraFrame (an orthonormal frame plus lens).
// Header-only: the shared shader types have internal linkage (see shader_lib.h), so functions
// that take or return them are defined in each translation unit that uses them.
#pragma once

#include <cmath>

#include "renderer/scene.h"
#include "renderer/shader_lib.h"

namespace glint {
namespace {

// aspect = width / height of the image being rendered. The frame is built in double and
// rounded once: in float, target - position overflows for points far apart, and a short up
// vector (length 1e-30, valid) squares to zero in normalize(cross(forward, up)), which gave a
// NaN frame. In double neither happens for any finite float input (validate_scene checks the
// same frame).
gpu::CameraFrame make_camera_frame(const Camera& camera, float aspect) {
  const glm::dvec3 forward = glm::normalize(glm::dvec3(camera.target) - glm::dvec3(camera.position));
  const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(camera.up)));
  const glm::dvec3 up = glm::cross(right, forward);
  float tan_half = std::tan(glm::radians(camera.vfov_deg) * 0.5f);
  return gpu::CameraFrame(camera.position, glm::vec3(right), glm::vec3(up), glm::vec3(forward),
                          tan_half, aspect,
                          camera.aperture_radius, camera.focus_distance);
}

// The primary ray through film position (x, y) in [0,1]^2 from the top-left, through the lens
// centre (no depth-of-field jitter): the editor's picking ray.
[[maybe_unused]] gpu::Ray camera_center_ray(const Camera& camera, float aspect, glm::vec2 film) {
  gpu::CameraFrame frame = make_camera_frame(camera, aspect);
  frame.aperture = 0;
  return gpu::camera_ray(frame, film, glm::vec2(0.5f));
}

}  // namespace
}  // namespace glint
