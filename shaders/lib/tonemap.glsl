// Display transform of the original program: exposure in stops, then the filmic curve
// (or a clamp), then gamma 1/2.2. Values are clamped to [0, 1] for display.
#ifndef GLINT_TONEMAP_GLSL
#define GLINT_TONEMAP_GLSL

const int TONEMAP_FILMIC = 0;
const int TONEMAP_LINEAR = 1;

float filmic_curve(float c) { return (0.9f * c * c + 0.02f * c) / (0.87f * c * c + 0.35f * c + 0.14f); }

float tonemap_channel(float c, float exposure, int mode) {
  float x = max(c, 0.0f) * exp2(exposure);
  x = mode == TONEMAP_FILMIC ? filmic_curve(x) : x;
  return pow(clamp(x, 0.0f, 1.0f), 1.0f / 2.2f);
}

vec3 tonemap(vec3 c, float exposure, int mode) {
  return vec3(tonemap_channel(c.x, exposure, mode), tonemap_channel(c.y, exposure, mode),
              tonemap_channel(c.z, exposure, mode));
}

#endif
