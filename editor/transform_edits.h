// Rotating and scaling objects about their centres (the viewport's gizmo), as functions on plain
// values: no UI. A quad is the corner p0 and its edges p0->p2 (local x) and p0->p1 (local y);
// p3 = p0 + both edges for a parallelogram.
#pragma once

#include <glm/glm.hpp>

#include "renderer/scene.h"

namespace glint {

// The quad turned by `radians` about `axis` (any non-zero vector; right-handed: positive turns
// counter-clockwise seen from the axis' tip) through its centre. Edge lengths, the angle
// between the edges and the centre stay. A zero or non-finite axis or angle returns it as is.
Quad rotate_quad(const Quad& quad, glm::vec3 axis, float radians);

// The quad with its edges p0->p2 multiplied by scale_x and p0->p1 by scale_y, about its centre
// (each corner moves along the edges; the plane and the centre stay). Factors must be positive
// and finite; anything else returns the quad as is, so that no drag can make it degenerate.
Quad scale_quad(const Quad& quad, float scale_x, float scale_y);

// The unit directions of the quad's local x (p0->p2) and y (p0->p1) edges; zero for an edge of
// zero length.
glm::vec3 quad_edge_x(const Quad& quad);
glm::vec3 quad_edge_y(const Quad& quad);

// A sphere's radius times `scale`, kept at least kMinRadius (positive, finite factors only).
constexpr float kMinRadius = 1e-4f;
float scaled_radius(float radius, float scale);

}  // namespace glint
