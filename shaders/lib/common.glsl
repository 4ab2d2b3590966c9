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

// Moves a ray origin off a surface so the new ray does not re-hit it (Wachter and Binder,
// "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems, ch. 6):
// a fixed number of float ulps away from the surface, so the offset scales with |p|,
// and a small absolute offset near the origin where ulps become tiny.
// `n` is the geometric normal on the side the new ray leaves from.
vec3 offset_ray_origin(vec3 p, vec3 n) {
  const float origin_band = 1.0f / 32.0f;
  const float float_scale = 1.0f / 65536.0f;
  const float int_scale = 256.0f;
  int ox = int(int_scale * n.x);
  int oy = int(int_scale * n.y);
  int oz = int(int_scale * n.z);
  float px = intBitsToFloat(floatBitsToInt(p.x) + (p.x < 0.0f ? -ox : ox));
  float py = intBitsToFloat(floatBitsToInt(p.y) + (p.y < 0.0f ? -oy : oy));
  float pz = intBitsToFloat(floatBitsToInt(p.z) + (p.z < 0.0f ? -oz : oz));
  return vec3(abs(p.x) < origin_band ? p.x + float_scale * n.x : px,
              abs(p.y) < origin_band ? p.y + float_scale * n.y : py,
              abs(p.z) < origin_band ? p.z + float_scale * n.z : pz);
}

#endif
