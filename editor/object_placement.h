// Where new and duplicated objects go (editor/scene_edits.h's add_sphere, add_quad, duplicate):
// clear of what is there, at orientations a person would type. Plain maths on scene values.
#pragma once

#include <glm/glm.hpp>

#include "renderer/scene.h"

namespace glint {

// The distance from a point to a quad (the parallelogram of p0 and its edges p0->p1, p0->p2).
float distance_to_quad(const Quad& quad, glm::vec3 point);
// Whether a sphere of this centre and radius would touch any sphere or quad of the scene.
bool touches_scene(const Scene& scene, glm::vec3 center, float radius);
// The centre nearest to `preferred` in the plane of `right` and `up` (unit, orthogonal), on a grid
// of steps of 2.5 radii up to 6 steps away, where the sphere touches nothing; `preferred` itself
// when it is free or no place on the grid is.
glm::vec3 free_sphere_center(const Scene& scene, glm::vec3 preferred, float radius, glm::vec3 right, glm::vec3 up);

// A view frame turned to the nearest axis-aligned one: forward along the world axis nearest to
// `forward`, up along the axis nearest to `up` among the other two, right = forward x up.
struct AxisFrame {
  glm::vec3 forward, right, up;
};
AxisFrame nearest_axis_frame(glm::vec3 forward, glm::vec3 up);

}  // namespace glint
