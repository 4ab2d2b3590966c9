// Constants, the ray type and small helpers shared by every shader and by the C++ tests.
// Written in the common subset of GLSL 4.50 and C++20 with GLM (see renderer/shader_lib.h):
// value parameters only, no swizzles, float literals with an `f` suffix, no recursion.
#ifndef GLINT_COMMON_GLSL
#define GLINT_COMMON_GLSL

const float PI = 3.14159265358979323846;
const float INV_PI = 0.31830988618379067154;
const float TWO_PI = 6.28318530717958647692;

struct Ray {
  vec3 origin;
  vec3 direction;
};

float max_component(vec3 v) { return max(v.x, max(v.y, v.z)); }

float luminance(vec3 c) { return dot(c, vec3(0.2126f, 0.7152f, 0.0722f)); }

bool is_finite(vec3 v) {
  return !(isnan(v.x) || isnan(v.y) || isnan(v.z) || isinf(v.x) || isinf(v.y) || isinf(v.z));
}

// The distance a spawned ray's origin must keep from a surface, for a hit point computed to a
// few ulps of `scale`: the largest coordinate magnitude that went into it (the hit point's own
// and the shape's defining points: max(|centre|, radius) for a sphere, the largest corner
// coordinate for a quad). A sphere of radius 1e5 used as a floor has its top near y = 0, but
// its points are only known to ulps of 1e5 (0.008): an offset in ulps of p alone (1e-7 there)
// would leave spawned rays below the computed surface (acne). SURFACE_OFFSET_EPS is 16 float
// epsilons: the rounding of a reprojected sphere point or a barycentric quad point is a few
// epsilons of `scale`, a ray leaving a sphere needs its origin outside by more than the
// rounding of |o - c|^2 - r^2 (about 3 eps r^2, i.e. 1.5 eps r of height), and a ray leaving a
// quad needs dot(p0 - o, n) to keep its sign (a few eps of the quad's size). hard_Reintersection
// (tests/unit/hard_cases_test.cpp) passes from 8 epsilons and fails at 4; 16 is twice the
// measured need. The small absolute term keeps the offset non-zero at the origin.
const float SURFACE_OFFSET_EPS = 16.0f / 8388608.0f;
const float SURFACE_OFFSET_MIN = 1e-30f;

float surface_offset_distance(vec3 p, float scale) {
  return SURFACE_OFFSET_EPS * max(max_component(abs(p)), scale) + SURFACE_OFFSET_MIN;
}

// p moved along the unit normal n (on the side the new ray leaves from) by
// surface_offset_distance: the rounding of p + d n is at most half an ulp of |p|, far below d.
vec3 offset_surface_point(vec3 p, vec3 n, float scale) {
  return p + surface_offset_distance(p, scale) * n;
}

#endif
