// Picking and click-to-focus: a ray through the clicked pixel, intersected with the shared
// shader intersection code (shaders/lib/intersect.glsl compiled as C++).
#pragma once

#include <optional>

#include <glm/glm.hpp>

#include "editor/document.h"
#include "renderer/scene.h"

namespace glint {

struct PickHit {
  Selection what;  // sphere or quad
  float t = 0;     // along the unit-length ray
  glm::vec3 point{0};
};

// film: the clicked position in [0,1]^2 from the top-left of the viewport; aspect = w / h.
std::optional<PickHit> pick(const Scene& scene, glm::vec2 film, float aspect);

// The focus distance (along the view direction, as docs/DESIGN.md defines it) that makes `point`
// sharp.
float focus_distance_for(const Camera& camera, glm::vec3 point);

}  // namespace glint
