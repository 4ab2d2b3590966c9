// Frames, warps and the GGX microfacet distribution. Local frames have the normal on +z.
#ifndef GLINT_SAMPLING_GLSL
#define GLINT_SAMPLING_GLSL

// Orthonormal basis around unit n without a singularity (Duff et al., "Building an
// Orthonormal Basis, Revisited", JCGT 2017). Columns: tangent, bitangent, n.
mat3 basis_from_normal(vec3 n) {
  float s = n.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (s + n.z);
  float b = n.x * n.y * a;
  return mat3(vec3(1.0f + s * n.x * n.x * a, s * b, -s * n.x), vec3(b, s + n.y * n.y * a, -n.y), n);
}

// Concentric map of the unit square onto the unit disk (Shirley and Chiu 1997).
vec2 sample_disk(vec2 u) {
  float x = 2.0f * u.x - 1.0f;
  float y = 2.0f * u.y - 1.0f;
  if (x == 0.0f && y == 0.0f) return vec2(0.0f);
  float r;
  float phi;
  if (abs(x) > abs(y)) {
    r = x;
    phi = (PI / 4.0f) * (y / x);
  } else {
    r = y;
    phi = (PI / 2.0f) - (PI / 4.0f) * (x / y);
  }
  return vec2(r * cos(phi), r * sin(phi));
}

// Cosine-weighted hemisphere around +z; pdf = cos(theta) / pi.
vec3 sample_cosine_hemisphere(vec2 u) {
  vec2 d = sample_disk(u);
  float z = sqrt(max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return vec3(d.x, d.y, z);
}

float fresnel_schlick(float f0, float cos_theta) {
  float m = clamp(1.0f - abs(cos_theta), 0.0f, 1.0f);
  float m2 = m * m;
  return f0 + (1.0f - f0) * m2 * m2 * m;
}

vec3 fresnel_schlick(vec3 f0, float cos_theta) {
  float m = clamp(1.0f - abs(cos_theta), 0.0f, 1.0f);
  float m2 = m * m;
  return f0 + (vec3(1.0f) - f0) * (m2 * m2 * m);
}

float dielectric_f0(float ior) {
  float r = (ior - 1.0f) / (ior + 1.0f);
  return r * r;
}

// GGX (Trowbridge-Reitz) normal distribution; cos_h = n.h.
float ggx_distribution(float alpha, float cos_h) {
  if (cos_h <= 0.0f) return 0.0f;
  float a2 = alpha * alpha;
  float d = cos_h * cos_h * (a2 - 1.0f) + 1.0f;
  return a2 / (PI * d * d);
}

// Smith masking for one direction; the separable G is the product over wo and wi.
float smith_g1(float alpha, float cos_v) {
  float c = abs(cos_v);
  float a2 = alpha * alpha;
  return 2.0f * c / (c + sqrt(a2 + (1.0f - a2) * c * c));
}

// A microfacet normal around +z with pdf D(h) cos(theta_h) (Walter et al. 2007).
vec3 sample_ggx_normal(float alpha, vec2 u) {
  float phi = TWO_PI * u.x;
  float tan2 = alpha * alpha * u.y / (1.0f - u.y);
  float cos_theta = 1.0f / sqrt(1.0f + tan2);
  // sin = tan * cos, not sqrt(1 - cos^2): near the pole 1 - cos^2 cancels (in float, cos is
  // 1 for tan2 < 6e-8, and at alpha = 0.03^2 theta was off by 9% on average).
  float sin_theta = sqrt(tan2) * cos_theta;
  return vec3(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
}

#endif
