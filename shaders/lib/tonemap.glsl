// Display transform of the original program: exposure in stops, then the filmic curve
// (or a clamp), then gamma 1/2.2. Values are clamped to [0, 1] for display.
#ifndef GLINT_TONEMAP_GLSL
#define GLINT_TONEMAP_GLSL

const int TONEMAP_FILMIC = 0;
const int TONEMAP_LINEAR = 1;

// (0.9c^2 + 0.02c) / (0.87c^2 + 0.35c + 0.14). Above c = 16 the same rational divided through
// by c^2 (in u = 1/c), which cannot overflow: c^2 is infinite from c = 2^64 and inf / inf is NaN,
// which the clamp turned into black. Both forms exceed 1 from c = 11.4 on (the curve tends to
// 0.9 / 0.87), so the displayed value is the same 1 on either side of the switch, and exactly
// 1 for every large finite c and for +inf (u = 0).
float filmic_curve(float c) {
  if (c > 16.0f) {
    float u = 1.0f / c;
    return (0.9f + 0.02f * u) / (0.87f + 0.35f * u + 0.14f * u * u);
  }
  return (0.9f * c * c + 0.02f * c) / (0.87f * c * c + 0.35f * c + 0.14f);
}

float tonemap_channel(float c, float exposure, int mode) {
  // Black stays black at any exposure (0 * exp2(200) = 0 * inf would be NaN).
  float x = c > 0.0f ? c * exp2(exposure) : 0.0f;
  x = mode == TONEMAP_FILMIC ? filmic_curve(x) : x;
  return pow(clamp(x, 0.0f, 1.0f), 1.0f / 2.2f);
}

vec3 tonemap(vec3 c, float exposure, int mode) {
  return vec3(tonemap_channel(c.x, exposure, mode), tonemap_channel(c.y, exposure, mode),
              tonemap_channel(c.z, exposure, mode));
}

#endif
