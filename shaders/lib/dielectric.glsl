// The refractive material of docs/DESIGN.md §7: one interface between two dielectrics, with
// the exact Fresnel reflectance of unpolarised light, Snell's law and total internal
// reflection; smooth (delta lobes) or rough (GGX reflection and transmission, Walter et al.
// 2007, "Microfacet Models for Refraction through Rough Surfaces", sampled from the visible
// normals as the other lobes). Notation as in bsdf.glsl: wo points to the viewer, wi to the
// light, n is the shading normal on wo's side. eta is the relative index: the index on the far
// side of the surface (where a transmitted wi lies) over the index on wo's side, so ior when
// the ray enters the material and 1 / ior when it leaves it (the path tracer decides which).
// Transmitted radiance is scaled by 1 / eta^2 (radiance over the squared index is what a ray
// carries unchanged; Veach 1997, ch. 5.2), so f(wo, wi) eta_o^2 = f(wi, wo) eta_i^2.
#ifndef GLINT_DIELECTRIC_GLSL
#define GLINT_DIELECTRIC_GLSL

// The Fresnel reflectance of unpolarised light arriving at cos_i > 0 (measured on the
// arriving side) at an interface of relative index eta (far side over arriving side): the mean
// of the s- and p-polarised reflectances (Born and Wolf, §1.5.2). 1 beyond the critical angle.
float fresnel_dielectric(float cos_i, float eta) {
  float c = clamp(cos_i, 0.0f, 1.0f);
  // sin^2 of the transmitted angle by Snell, (1 - c^2) / eta^2, written (1 - c)(1 + c) so
  // that it does not cancel near normal incidence.
  float sin2_t = (1.0f - c) * (1.0f + c) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  float cos_t = sqrt(1.0f - sin2_t);
  float r_s = (c - eta * cos_t) / (c + eta * cos_t);
  float r_p = (eta * c - cos_t) / (eta * c + cos_t);
  return 0.5f * (r_s * r_s + r_p * r_p);
}

// wo (cos_o = m.wo > 0) refracted through the surface of normal m: the direction on the far
// side by Snell's law, or vec3(0) at total internal reflection.
vec3 refract_direction(vec3 wo, vec3 m, float eta) {
  float c = dot(wo, m);
  float sin2_t = (1.0f - c) * (1.0f + c) / (eta * eta);
  if (sin2_t >= 1.0f) return vec3(0.0f);
  float cos_t = sqrt(1.0f - sin2_t);
  return normalize((c / eta - cos_t) * m - wo / eta);
}

// The microfacet normal that refracts wo into wi (wi on the far side): -(wo + eta wi),
// normalised and turned to n's side (Walter et al. 2007, eq. 16). vec3(0) when wo and wi do
// not make a refraction through a visible microfacet (m.wo > 0 and m.wi < 0 both needed).
vec3 transmission_half_vector(vec3 n, vec3 wo, vec3 wi, float eta) {
  vec3 h = wo + eta * wi;
  float len2 = dot(h, h);
  if (!(len2 > 0.0f)) return vec3(0.0f);
  h = h / sqrt(len2);
  if (dot(n, h) < 0.0f) h = -h;
  if (!(dot(wo, h) > 0.0f) || !(dot(wi, h) < 0.0f)) return vec3(0.0f);
  return h;
}

// The rough interface's transmission f |n.wi| for wi on the far side (n.wi < 0), without the
// colour (Walter et al. 2007, eq. 21, for radiance: divided by eta^2):
// |wi.h| |wo.h| (1 - F) D G / (|n.wo| (wo.h + eta wi.h)^2).
float rough_dielectric_transmission(float alpha, vec3 n, vec3 wo, vec3 wi, float eta) {
  vec3 h = transmission_half_vector(n, wo, wi, eta);
  if (dot(h, h) == 0.0f) return 0.0f;
  float cos_o = abs(dot(n, wo));
  if (cos_o == 0.0f) return 0.0f;
  float cos_oh = dot(wo, h);
  float cos_ih = dot(wi, h);
  float denom = cos_oh + eta * cos_ih;
  float f = 1.0f - fresnel_dielectric(cos_oh, eta);
  return abs(cos_ih) * cos_oh * f * ggx_distribution(alpha, dot(n, h)) * smith_g1(alpha, dot(n, wo)) *
         smith_g1(alpha, dot(n, wi)) / (cos_o * denom * denom);
}

// The pdf of that wi when h is drawn from the visible normals of wo and the transmission lobe
// is then chosen with probability 1 - F(wo.h): D_wo(h) (1 - F) times the Jacobian
// eta^2 |wi.h| / (wo.h + eta wi.h)^2 of the refraction (Walter et al. 2007, eq. 17).
float rough_dielectric_transmission_pdf(float alpha, vec3 n, vec3 wo, vec3 wi, float eta) {
  vec3 h = transmission_half_vector(n, wo, wi, eta);
  if (dot(h, h) == 0.0f) return 0.0f;
  float cos_oh = dot(wo, h);
  float cos_ih = dot(wi, h);
  float denom = cos_oh + eta * cos_ih;
  float f = 1.0f - fresnel_dielectric(cos_oh, eta);
  return smith_g1_over_cos(alpha, dot(n, wo)) * cos_oh * ggx_distribution(alpha, dot(n, h)) * f *
         eta * eta * abs(cos_ih) / (denom * denom);
}

#endif
