// The limits that come from the renderer's 32-bit floats, checked by validate_scene on the
// values the GPU will see (float products, coordinates relative to the render origin), not on
// the doubles of the file: each value can be finite while a product or square overflows.
#pragma once

#include <vector>

#include "renderer/project_error.h"
#include "renderer/scene.h"

namespace glint {

// Radiance: emission components, the environment's colour times its intensity (as the shader
// gets it), and the intensity of a textured environment. The accumulation sums samples of up
// to a few times this radiance in float (and BSDF values of up to about 1e6 multiply it first),
// so this leaves a factor of about 1e12 below FLT_MAX. An emitter of 1e20 displays white.
constexpr float kMaxRadiance = 1e20f;

// Coordinates: every component of the camera's position and target, sphere centres and radii
// and quad corners. A quad's hit distance divides dot(p0 - o, n) by dot(d, n) with n the cross
// product of two edges, a product of three coordinates (up to 2 * (2L)^2 * sqrt(3) * 2L for
// coordinates of magnitude L): it stays below FLT_MAX up to 1e12 (and sphere tests square them).
constexpr float kMaxCoordinate = 1e12f;

// The problems (file name empty, JSON path and problem), for a scene whose values are already
// known to be finite where they matter (validate_scene reports non-finite ones first; they are
// skipped here). Besides the limits above: the camera must not be closer to a sphere's surface
// than the float rounding of the sphere's position relative to the camera (half an ulp of the
// larger of its radius and its centre's largest coordinate, relative to the render origin):
// nearer than that, the renderer cannot tell on which side of the surface the camera is (a
// floor sphere of radius 1e8 seen from 1 above rendered black).
std::vector<ProjectError> check_float_limits(const Scene& scene);

}  // namespace glint
