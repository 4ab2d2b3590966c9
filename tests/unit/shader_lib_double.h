// The shared shader maths (shaders/lib/*.glsl) compiled as C++ in DOUBLE precision, as
// glint::gpu_double::*, next to the float build of renderer/shader_lib.h (glint::gpu::*).
// The tests run the same checks in both precisions (docs/DESIGN.md §8): a failure only in float
// points at rounding, a failure in both at the maths.
//
// How: `float` is #defined to `double` around the #includes, the GLSL vector and matrix names
// are the GLM double types, and the GLSL files' `f`-suffixed literals (which stay float) are
// handled by the mixed float/double overloads below. Those overloads live in this namespace
// only, so nothing outside it changes. The GLSL files are included unchanged.
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

// The float build first: it owns the include guards of the GLSL files, which are undefined
// below so that the same files can be included a second time.
#include "renderer/shader_lib.h"

namespace glint::gpu_double {

using uint = std::uint32_t;
using vec2 = glm::dvec2;
using vec3 = glm::dvec3;
using vec4 = glm::dvec4;
using mat2 = glm::dmat2;
using mat3 = glm::dmat3;
using mat4 = glm::dmat4;
using glm::ivec2;
using glm::ivec3;
using glm::ivec4;
using glm::uvec2;
using glm::uvec3;
using glm::uvec4;

// Vector functions (dot, cross, normalize, reflect, vector min/max/abs, ...). The scalar
// overloads below hide glm's scalar templates for unqualified calls; calls with GLM vector
// arguments still find glm's versions by argument-dependent lookup.
using namespace glm;

// Scalar functions, non-template so that mixed float/double arguments (a double variable
// and an `f` literal) convert instead of failing template deduction.
inline double abs(double x) { return std::fabs(x); }
inline double sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }
inline double min(double a, double b) { return b < a ? b : a; }
inline double max(double a, double b) { return a < b ? b : a; }
inline int min(int a, int b) { return b < a ? b : a; }
inline int max(int a, int b) { return a < b ? b : a; }
inline uint min(uint a, uint b) { return b < a ? b : a; }
inline uint max(uint a, uint b) { return a < b ? b : a; }
inline double clamp(double x, double lo, double hi) { return min(max(x, lo), hi); }
inline int clamp(int x, int lo, int hi) { return min(max(x, lo), hi); }
inline double mix(double a, double b, double t) { return a + (b - a) * t; }
inline double step(double edge, double x) { return x < edge ? 0.0 : 1.0; }
inline double smoothstep(double e0, double e1, double x) {
  double t = clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}
inline double floor(double x) { return std::floor(x); }
inline double ceil(double x) { return std::ceil(x); }
inline double fract(double x) { return x - std::floor(x); }
inline double mod(double x, double y) { return x - y * std::floor(x / y); }
inline double sqrt(double x) { return std::sqrt(x); }
inline double inversesqrt(double x) { return 1.0 / std::sqrt(x); }
inline double pow(double x, double y) { return std::pow(x, y); }
inline double exp(double x) { return std::exp(x); }
inline double exp2(double x) { return std::exp2(x); }
inline double log(double x) { return std::log(x); }
inline double log2(double x) { return std::log2(x); }
inline double sin(double x) { return std::sin(x); }
inline double cos(double x) { return std::cos(x); }
inline double tan(double x) { return std::tan(x); }
inline double asin(double x) { return std::asin(x); }
inline double acos(double x) { return std::acos(x); }
inline double atan(double y_over_x) { return std::atan(y_over_x); }
inline double atan(double y, double x) { return std::atan2(y, x); }
inline bool isnan(double x) { return std::isnan(x); }
inline bool isinf(double x) { return std::isinf(x); }

// Mixed float-scalar/double-vector arithmetic (`0.5f * v`, `v / 2.0f`): glm's operator
// templates want the scalar in the vector's own type.
#define GLINT_DOUBLE_MIXED_OPS(V)                                          \
  inline V operator+(float s, const V& v) { return double(s) + v; }        \
  inline V operator-(float s, const V& v) { return double(s) - v; }        \
  inline V operator*(float s, const V& v) { return double(s) * v; }        \
  inline V operator/(float s, const V& v) { return double(s) / v; }        \
  inline V operator+(const V& v, float s) { return v + double(s); }        \
  inline V operator-(const V& v, float s) { return v - double(s); }        \
  inline V operator*(const V& v, float s) { return v * double(s); }        \
  inline V operator/(const V& v, float s) { return v / double(s); }
GLINT_DOUBLE_MIXED_OPS(glm::dvec2)
GLINT_DOUBLE_MIXED_OPS(glm::dvec3)
GLINT_DOUBLE_MIXED_OPS(glm::dvec4)
#undef GLINT_DOUBLE_MIXED_OPS

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-variable"
namespace {
#undef GLINT_COMMON_GLSL
#undef GLINT_RNG_GLSL
#undef GLINT_SOBOL_GLSL
#undef GLINT_MAPPING_GLSL
#undef GLINT_SAMPLING_GLSL
#undef GLINT_INTERSECT_GLSL
#undef GLINT_CAMERA_GLSL
#undef GLINT_DIELECTRIC_GLSL
#undef GLINT_BSDF_GLSL
#undef GLINT_TONEMAP_GLSL
#undef GLINT_LIGHTS_GLSL
#undef GLINT_ENVIRONMENT_SAMPLING_GLSL
// The accessors of environment_sampling.glsl over the same float tables as the float build.
ivec2 env_distribution_size() {
  return ivec2(gpu::environment_tables.width, gpu::environment_tables.height);
}
double env_marginal_cdf(int i) { return gpu::environment_tables.marginal_cdf[i]; }
double env_conditional_cdf(int row, int i) {
  return gpu::environment_tables.conditional_cdf[std::size_t(row) * (gpu::environment_tables.width + 1) + i];
}
#define float double
#include "shaders/lib/common.glsl"
#include "shaders/lib/rng.glsl"
#include "shaders/lib/sobol.glsl"
#include "shaders/lib/mapping.glsl"
#include "shaders/lib/sampling.glsl"
#include "shaders/lib/intersect.glsl"
#include "shaders/lib/camera.glsl"
#include "shaders/lib/dielectric.glsl"
#include "shaders/lib/bsdf.glsl"
#include "shaders/lib/tonemap.glsl"
#include "shaders/lib/lights.glsl"
#include "shaders/lib/environment_sampling.glsl"
#undef float
}  // namespace
#pragma GCC diagnostic pop

}  // namespace glint::gpu_double
