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

// Concentric map of the unit square onto the unit disk (Shirley and Chiu 1997). Written with
// selects and one division rather than an `if` per octant pair: on a SIMD CPU (llvmpipe) an
// `if` whose lanes disagree, as random points do here, runs both sides, with a division each.
// The values are the same as with the `if`.
vec2 sample_disk(vec2 u) {
  float x = 2.0f * u.x - 1.0f;
  float y = 2.0f * u.y - 1.0f;
  bool x_major = abs(x) > abs(y);
  float r = x_major ? x : y;
  // At the centre (r = 0) the divisor is 1, so that no lane divides 0 by 0; r * cos(phi) is 0.
  float ratio = (x_major ? y : x) / (r == 0.0f ? 1.0f : r);
  float phi = x_major ? (PI / 4.0f) * ratio : (PI / 2.0f) - (PI / 4.0f) * ratio;
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

// G1(v) / |n.v| without the division: 2 / (c + sqrt(a^2 + (1 - a^2) c^2)). Finite at grazing
// (2 / alpha at c = 0), where G1 and c both go to zero and their quotient would be 0 / 0.
float smith_g1_over_cos(float alpha, float cos_v) {
  float c = abs(cos_v);
  float a2 = alpha * alpha;
  return 2.0f / (c + sqrt(a2 + (1.0f - a2) * c * c));
}

// Density of the visible normals seen from wo (local frame, wo.z = n.wo >= 0):
// D_wo(h) = G1(wo) max(0, wo.h) D(h) / (n.wo) (Heitz 2018, eq. 1).
float ggx_visible_normal_pdf(float alpha, vec3 wo, vec3 h) {
  float cos_oh = dot(wo, h);
  if (!(cos_oh > 0.0f)) return 0.0f;  // also NaN
  return smith_g1_over_cos(alpha, wo.z) * cos_oh * ggx_distribution(alpha, h.z);
}

// A microfacet normal around +z drawn from D_wo(h), for wo in the local frame with wo.z >= 0:
// Dupuy and Benyoub, "Sound and Complete Visible Normal Sampling of GGX" (2023, spherical
// caps; the same distribution as Heitz 2018). In the configuration stretched to alpha = 1 the
// visible normals are c + v, with v the stretched wo and c uniform on the spherical cap
// z > -v.z; the result is unstretched by (alpha x, alpha y, z).
vec3 sample_ggx_visible_normal(float alpha, vec3 wo, vec2 u) {
  vec3 v = normalize(vec3(alpha * wo.x, alpha * wo.y, max(wo.z, 0.0f)));
  float phi = TWO_PI * u.x;
  // z = 1 - u.y (1 + v.z) is uniform on (-v.z, 1]. sin^2 = (1 - z)(1 + z), not 1 - z^2: near
  // the cap's pole (small u.y) 1 - z^2 cancels in float, and at alpha = 0.03^2 that pole is
  // where the normals closest to n come from (the old sampler's cos/sin issue, once more).
  float one_minus_z = u.y * (1.0f + v.z);
  float z = 1.0f - one_minus_z;
  float sin_theta = sqrt(max(0.0f, one_minus_z * (2.0f - one_minus_z)));
  vec3 h = vec3(sin_theta * cos(phi) + v.x, sin_theta * sin(phi) + v.y, max(z + v.z, 0.0f));
  // h = 0 needs c = -v exactly (u.y within 2^-24 of 1 and phi exactly opposite): measure
  // zero, but normalize(0) is NaN; the pole is a harmless stand-in.
  vec3 m = vec3(alpha * h.x, alpha * h.y, h.z);
  if (dot(m, m) == 0.0f) return vec3(0.0f, 0.0f, 1.0f);
  return normalize(m);
}

#endif
