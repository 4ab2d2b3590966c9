// The materials of docs/DESIGN.md §7 (LittleCG ch. 5 with Schlick Fresnel, and the refractive
// dielectric of dielectric.glsl): evaluation, sampling and pdf, consistent with each other. All
// directions are unit vectors in world space; n is the shading normal already flipped to the
// side of wo. eval returns f |n.wi|. For the refractive type, `ior` is the relative index eta of
// dielectric.glsl (ior entering, 1 / ior leaving).
#ifndef GLINT_BSDF_GLSL
#define GLINT_BSDF_GLSL

// Each type's code is its row's index in renderer/material_types.h (unit.MaterialTypes checks).
const int MATERIAL_MATTE = 0;
const int MATERIAL_REFLECTIVE = 1;
const int MATERIAL_GLOSSY = 2;
const int MATERIAL_TRANSPARENT = 3;
const int MATERIAL_REFRACTIVE = 4;

// Below this roughness, reflective, transparent and refractive surfaces are perfectly smooth
// (delta).
const float DELTA_ROUGHNESS = 0.03f;

struct SurfaceMaterial {
  int type;
  vec3 color;
  float roughness;
  float ior;
};

struct BsdfSample {
  vec3 wi;
  vec3 weight;  // f |n.wi| / pdf, or the delta lobe's weight
  float pdf;    // solid-angle pdf; 0 for delta lobes
  bool delta;
  bool valid;
};

// A refractive interface between equal indices (eta 1) is smooth at any roughness: every
// microfacet passes the ray on unbent, so the lobe is a delta at -wo.
bool is_delta_material(SurfaceMaterial m) {
  if (m.type == MATERIAL_REFRACTIVE) return m.roughness < DELTA_ROUGHNESS || m.ior == 1.0f;
  return (m.type == MATERIAL_REFLECTIVE || m.type == MATERIAL_TRANSPARENT) &&
         m.roughness < DELTA_ROUGHNESS;
}

float ggx_alpha(SurfaceMaterial m) {
  float r = m.type == MATERIAL_GLOSSY ? max(m.roughness, DELTA_ROUGHNESS) : m.roughness;
  return r * r;
}

vec3 mirror_through_plane(vec3 w, vec3 n) { return w - 2.0f * dot(n, w) * n; }

// D G / (4 |n.wo| |n.wi|) |n.wi| for the half vector h of a reflection.
float microfacet_reflection(float alpha, vec3 n, vec3 h, vec3 wo, vec3 wi) {
  float cos_o = abs(dot(n, wo));
  if (cos_o == 0.0f) return 0.0f;
  return ggx_distribution(alpha, dot(n, h)) * smith_g1(alpha, dot(n, wo)) *
         smith_g1(alpha, dot(n, wi)) / (4.0f * cos_o);
}

// pdf of wi = reflect(-wo, h) when h is drawn from the visible normals D_wo(h): D_wo(h) times
// the Jacobian 1 / (4 |wo.h|) of the reflection, i.e. G1(wo) D(h) / (4 n.wo) for wo.h > 0
// (Heitz 2018, eq. 17). Written with G1(wo) / n.wo in one piece, so that it stays finite at
// grazing wo; sample weights become F G1(wi), bounded by 1 at every angle.
float microfacet_reflection_pdf(float alpha, vec3 n, vec3 h, vec3 wo) {
  float cos_oh = dot(wo, h);
  if (!(cos_oh > 0.0f)) return 0.0f;  // also NaN (h of wi = -wo)
  return smith_g1_over_cos(alpha, dot(n, wo)) * ggx_distribution(alpha, dot(n, h)) * 0.25f;
}

// Visible-normal sample around n for wo (world space), as a world-space microfacet normal.
vec3 sample_microfacet_normal(float alpha, mat3 frame, vec3 wo, vec2 u) {
  vec3 wo_local = vec3(dot(frame[0], wo), dot(frame[1], wo), dot(frame[2], wo));
  return frame * sample_ggx_visible_normal(alpha, wo_local, u);
}

// Material types that no primitive uses are compiled out of the trace shader with
// GLINT_NO_MATTE, GLINT_NO_REFLECTIVE, GLINT_NO_GLOSSY, GLINT_NO_TRANSPARENT and
// GLINT_NO_REFRACTIVE (renderer/shader_features.h); with none defined (the C++ build) every
// branch is kept.
#if !defined(GLINT_NO_REFLECTIVE) || !defined(GLINT_NO_GLOSSY) || !defined(GLINT_NO_TRANSPARENT) || \
    !defined(GLINT_NO_REFRACTIVE)
#define GLINT_HAS_MICROFACETS
#endif

#if !defined(GLINT_NO_REFRACTIVE)
// The rough refractive interface: GGX reflection with the exact Fresnel term, or transmission.
vec3 eval_rough_dielectric(SurfaceMaterial m, vec3 n, vec3 wo, vec3 wi) {
  float alpha = ggx_alpha(m);
  if (dot(n, wi) > 0.0f) {
    vec3 h = normalize(wo + wi);
    if (!(dot(wo, h) > 0.0f)) return vec3(0.0f);
    return vec3(fresnel_dielectric(dot(wo, h), m.ior) * microfacet_reflection(alpha, n, h, wo, wi));
  }
  return m.color * rough_dielectric_transmission(alpha, n, wo, wi, m.ior);
}

float pdf_rough_dielectric(SurfaceMaterial m, vec3 n, vec3 wo, vec3 wi) {
  float alpha = ggx_alpha(m);
  if (dot(n, wi) > 0.0f) {
    vec3 h = normalize(wo + wi);
    if (!(dot(wo, h) > 0.0f)) return 0.0f;
    return fresnel_dielectric(dot(wo, h), m.ior) * microfacet_reflection_pdf(alpha, n, h, wo);
  }
  return rough_dielectric_transmission_pdf(alpha, n, wo, wi, m.ior);
}

// Smooth: reflection with probability F(n.wo) at weight 1, otherwise Snell's refraction at
// weight color / eta^2 (F = 1 beyond the critical angle: total internal reflection). Rough: a
// visible normal h, then reflection through it with probability F(wo.h), otherwise refraction
// through it.
BsdfSample sample_dielectric(SurfaceMaterial m, vec3 n, vec3 wo, float u_lobe, vec2 u) {
  BsdfSample invalid = BsdfSample(vec3(0.0f), vec3(0.0f), 0.0f, false, false);
  float eta = m.ior;
  if (is_delta_material(m)) {
    float cos_o = dot(n, wo);
    if (u_lobe < fresnel_dielectric(cos_o, eta)) {
      return BsdfSample(reflect(-wo, n), vec3(1.0f), 0.0f, true, true);
    }
    vec3 t = refract_direction(wo, n, eta);
    if (dot(t, t) == 0.0f) return invalid;  // (F is 1 there: not reached)
    return BsdfSample(t, m.color / (eta * eta), 0.0f, true, true);
  }
  vec3 h = sample_microfacet_normal(ggx_alpha(m), basis_from_normal(n), wo, u);
  vec3 wi;
  if (u_lobe < fresnel_dielectric(dot(wo, h), eta)) {
    wi = reflect(-wo, h);
    if (dot(n, wi) <= 0.0f) return invalid;
  } else {
    wi = refract_direction(wo, h, eta);
    if (!(dot(n, wi) < 0.0f)) return invalid;
  }
  float pdf = pdf_rough_dielectric(m, n, wo, wi);
  if (!(pdf > 0.0f)) return invalid;
  return BsdfSample(wi, eval_rough_dielectric(m, n, wo, wi) / pdf, pdf, false, true);
}
#endif

vec3 eval_bsdf(SurfaceMaterial m, vec3 n, vec3 wo, vec3 wi) {
  if (is_delta_material(m)) return vec3(0.0f);
#if !defined(GLINT_NO_REFRACTIVE)
  if (m.type == MATERIAL_REFRACTIVE) return eval_rough_dielectric(m, n, wo, wi);
#endif
  float cos_i = dot(n, wi);
  float cos_o = dot(n, wo);
#if !defined(GLINT_NO_MATTE)
  if (m.type == MATERIAL_MATTE) return cos_i > 0.0f ? m.color * (cos_i * INV_PI) : vec3(0.0f);
#endif
  float alpha = ggx_alpha(m);
#if !defined(GLINT_NO_REFLECTIVE)
  if (m.type == MATERIAL_REFLECTIVE) {
    if (cos_i <= 0.0f) return vec3(0.0f);
    vec3 h = normalize(wo + wi);
    return fresnel_schlick(m.color, dot(h, wi)) * microfacet_reflection(alpha, n, h, wo, wi);
  }
#endif
  float f0 = dielectric_f0(m.ior);
#if !defined(GLINT_NO_GLOSSY)
  if (m.type == MATERIAL_GLOSSY) {
    if (cos_i <= 0.0f) return vec3(0.0f);
    vec3 h = normalize(wo + wi);
    float coat = fresnel_schlick(f0, dot(h, wi)) * microfacet_reflection(alpha, n, h, wo, wi);
    vec3 base = m.color * ((1.0f - fresnel_schlick(f0, cos_o)) * INV_PI * cos_i);
    return base + vec3(coat);
  }
#endif
#if !defined(GLINT_NO_TRANSPARENT)
  // Rough thin glass: reflection, or transmission mirrored through the surface plane.
  if (cos_i > 0.0f) {
    vec3 h = normalize(wo + wi);
    return vec3(fresnel_schlick(f0, dot(h, wi)) * microfacet_reflection(alpha, n, h, wo, wi));
  }
  vec3 wr = mirror_through_plane(wi, n);
  vec3 h = normalize(wo + wr);
  return m.color * ((1.0f - fresnel_schlick(f0, dot(h, wo))) * microfacet_reflection(alpha, n, h, wo, wr));
#else
  return vec3(0.0f);
#endif
}

float pdf_bsdf(SurfaceMaterial m, vec3 n, vec3 wo, vec3 wi) {
  if (is_delta_material(m)) return 0.0f;
#if !defined(GLINT_NO_REFRACTIVE)
  if (m.type == MATERIAL_REFRACTIVE) return pdf_rough_dielectric(m, n, wo, wi);
#endif
  float cos_i = dot(n, wi);
#if !defined(GLINT_NO_MATTE)
  if (m.type == MATERIAL_MATTE) return cos_i > 0.0f ? cos_i * INV_PI : 0.0f;
#endif
  float alpha = ggx_alpha(m);
#if !defined(GLINT_NO_REFLECTIVE)
  if (m.type == MATERIAL_REFLECTIVE) {
    return cos_i > 0.0f ? microfacet_reflection_pdf(alpha, n, normalize(wo + wi), wo) : 0.0f;
  }
#endif
  float p_reflect = fresnel_schlick(dielectric_f0(m.ior), dot(n, wo));
#if !defined(GLINT_NO_GLOSSY)
  if (m.type == MATERIAL_GLOSSY) {
    if (cos_i <= 0.0f) return 0.0f;
    return p_reflect * microfacet_reflection_pdf(alpha, n, normalize(wo + wi), wo) +
           (1.0f - p_reflect) * cos_i * INV_PI;
  }
#endif
#if !defined(GLINT_NO_TRANSPARENT)
  if (cos_i > 0.0f) return p_reflect * microfacet_reflection_pdf(alpha, n, normalize(wo + wi), wo);
  vec3 wr = mirror_through_plane(wi, n);
  return (1.0f - p_reflect) * microfacet_reflection_pdf(alpha, n, normalize(wo + wr), wo);
#else
  return 0.0f;
#endif
}

// u_lobe picks a lobe, u drives the direction; both uniform in [0,1).
BsdfSample sample_bsdf(SurfaceMaterial m, vec3 n, vec3 wo, float u_lobe, vec2 u) {
  BsdfSample invalid = BsdfSample(vec3(0.0f), vec3(0.0f), 0.0f, false, false);
  float cos_o = dot(n, wo);
#if !defined(GLINT_NO_REFRACTIVE)
  if (m.type == MATERIAL_REFRACTIVE) return sample_dielectric(m, n, wo, u_lobe, u);
#endif
#if !defined(GLINT_NO_REFLECTIVE)
  if (m.type == MATERIAL_REFLECTIVE && m.roughness < DELTA_ROUGHNESS) {
    return BsdfSample(reflect(-wo, n), fresnel_schlick(m.color, cos_o), 0.0f, true, true);
  }
#endif
  float f0 = dielectric_f0(m.ior);
#if !defined(GLINT_NO_TRANSPARENT)
  if (m.type == MATERIAL_TRANSPARENT && m.roughness < DELTA_ROUGHNESS) {
    // Choosing reflection with probability F makes both weights free of F.
    if (u_lobe < fresnel_schlick(f0, cos_o)) return BsdfSample(reflect(-wo, n), vec3(1.0f), 0.0f, true, true);
    return BsdfSample(-wo, m.color, 0.0f, true, true);
  }
#endif
  mat3 frame = basis_from_normal(n);
  // The cosine lobe: matte, or the base of glossy (chosen with probability 1 - F).
  bool cosine_lobe = false;
#if !defined(GLINT_NO_MATTE)
  cosine_lobe = m.type == MATERIAL_MATTE;
#endif
#if !defined(GLINT_NO_GLOSSY)
  cosine_lobe = cosine_lobe || (m.type == MATERIAL_GLOSSY && u_lobe >= fresnel_schlick(f0, cos_o));
#endif
  vec3 wi;
#if !defined(GLINT_HAS_MICROFACETS)
  wi = frame * sample_cosine_hemisphere(u);
#else
  if (cosine_lobe) {
    wi = frame * sample_cosine_hemisphere(u);
  } else {
    vec3 h = sample_microfacet_normal(ggx_alpha(m), frame, wo, u);
    wi = reflect(-wo, h);
    if (dot(n, wi) <= 0.0f) return invalid;
#if !defined(GLINT_NO_TRANSPARENT)
    if (m.type == MATERIAL_TRANSPARENT && u_lobe >= fresnel_schlick(f0, cos_o)) {
      wi = mirror_through_plane(wi, n);
    }
#endif
  }
#endif
  float pdf = pdf_bsdf(m, n, wo, wi);
  if (!(pdf > 0.0f)) return invalid;
  return BsdfSample(wi, eval_bsdf(m, n, wo, wi) / pdf, pdf, false, true);
}

#endif
