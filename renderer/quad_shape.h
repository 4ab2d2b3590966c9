// Whether a quad's two triangles form one flat convex polygon, so that the trace shader may
// test it with intersect_planar_quad (shaders/lib/intersect.glsl: the plane's t, then the four
// boundary edges) instead of as two triangles.
#pragma once

#include <array>

#include <glm/glm.hpp>

namespace glint {

// Corners as in Quad: triangles (p0, p1, p2) and (p1, p3, p2), boundary p0 p1 p3 p2. True when
// p3 lies within 2^-23 of the quad's extent (its largest corner distance) of the plane of
// (p0, p1, p2) and the boundary turns one way at every corner (straight corners allowed).
// The tolerance: after camera-relative packing (gpu_scene.h) the deviation is still a few
// float epsilons of the packed corners' magnitude, which is below the 16 epsilons a spawned
// ray keeps from a surface (SURFACE_OFFSET_EPS), so the plane of the first triangle stands in
// for the second. Computed in double. Degenerate quads (no area) are not planar convex.
bool quad_is_planar_convex(const std::array<glm::vec3, 4>& corners);

// True when the quad is a parallelogram with area: p3 within 2^-21 of its longer diagonal of
// p1 + p2 - p0 (rectangles included; the tolerance leaves room for corners rounded to float).
// Such a light is sampled by the affine map of its two edges (shaders/lib/lights.glsl,
// sample_parallelogram_light), which covers the quad up to that tolerance: what it misses or
// adds is a sliver of at most that fraction of the light. Computed in double.
bool quad_is_parallelogram(const std::array<glm::vec3, 4>& corners);

}  // namespace glint
