// Light sampling for next-event estimation: spheres (cone of directions, Shirley et al. 1996 /
// pbrt-v4 Sphere::Sample) and quads (area sampling of the two triangles, or of a parallelogram
// as a whole), their solid-angle pdfs, and Veach's power heuristic. Needs common.glsl and
// sampling.glsl (basis_from_normal).
#ifndef GLINT_LIGHTS_GLSL
#define GLINT_LIGHTS_GLSL

// wi: unit direction from the shading point p to the sampled point y; dist = |y - p|;
// pdf: solid angle at p. valid is false when nothing could be sampled (pdf 0).
struct LightSample {
  vec3 wi;
  float dist;
  float pdf;
  bool valid;
};

LightSample invalid_light_sample() { return LightSample(vec3(0.0f), 0.0f, 0.0f, false); }

// Inside or on the sphere: every point of it is visible, so it is sampled by area. The same
// test decides for the sampler and for the pdf, so both always use the same density.
bool inside_sphere(vec3 p, vec3 center, float radius) {
  vec3 d = p - center;
  return dot(d, d) <= radius * radius;
}

// The area pdf of a sphere point y converted to solid angle at p: |y - p|^2 / (|cos| 4 pi r^2).
float sphere_area_pdf(vec3 p, vec3 center, float radius, vec3 y) {
  vec3 to_y = y - p;
  float dist2 = dot(to_y, to_y);
  vec3 n = normalize(y - center);
  float cos_y = abs(dot(n, to_y)) * inversesqrt(dist2);
  if (!(dist2 > 0.0f) || !(cos_y > 0.0f)) return 0.0f;
  return dist2 / (cos_y * 4.0f * PI * radius * radius);
}

// 1 - cos(theta_max) of the cone that a sphere subtends from distance dc (> radius) as
// sin^2 / (1 + cos): 1 - sqrt(1 - s2) in float is 0 for r/dc < 2.4e-4 (s2 below an ulp of 1).
// s2 = (r / dc)^2 is formed from the ratio, which stays accurate for tiny r.
float sphere_cone_one_minus_cos(float radius, float dc) {
  float ratio = radius / dc;
  float sin2 = ratio * ratio;
  float cos_max = sqrt(max(0.0f, 1.0f - sin2));
  return sin2 / (1.0f + cos_max);
}

LightSample sample_sphere_light(vec3 p, vec3 center, float radius, vec2 u) {
  if (inside_sphere(p, center, radius)) {
    // Uniform on the sphere: z = 1 - 2 u, then converted to solid angle at p.
    float z = 1.0f - 2.0f * u.x;
    float s = sqrt(max(0.0f, (1.0f - z) * (1.0f + z)));
    float phi = TWO_PI * u.y;
    vec3 n = vec3(s * cos(phi), s * sin(phi), z);
    vec3 y = center + radius * n;
    vec3 to_y = y - p;
    float dist = length(to_y);
    float pdf = sphere_area_pdf(p, center, radius, y);
    if (!(dist > 0.0f) || !(pdf > 0.0f)) return invalid_light_sample();
    return LightSample(to_y / dist, dist, pdf, true);
  }
  vec3 axis = center - p;
  float dc = length(axis);
  axis = axis / dc;
  float one_minus_cos_max = sphere_cone_one_minus_cos(radius, dc);
  // Uniform in the cone: 1 - cos(theta) = u (1 - cos_max). sin^2 = (1 - cos)(1 + cos) without
  // forming 1 - cos^2, so directions inside a cone of 1e-6 radians keep their spread.
  float omc = u.x * one_minus_cos_max;
  float cos_t = 1.0f - omc;
  float sin2_t = omc * (2.0f - omc);
  float sin_t = sqrt(sin2_t);
  float phi = TWO_PI * u.y;
  mat3 frame = basis_from_normal(axis);
  vec3 wi = normalize(frame * vec3(sin_t * cos(phi), sin_t * sin(phi), cos_t));
  // The nearer root of |p + t wi - c| = r: t = dc cos - sqrt(r^2 - dc^2 sin^2), written as
  // (dc^2 - r^2) / (dc cos + sqrt(...)) (the product of the roots) to avoid cancellation.
  // r^2 - dc^2 sin^2 = dc^2 (ratio^2 - sin^2): both small terms stay relative to each other.
  float ratio = radius / dc;
  float h2 = max(0.0f, ratio * ratio - sin2_t);
  float dist = (dc - radius) * (dc + radius) / (dc * (cos_t + sqrt(h2)));
  float pdf = 1.0f / (TWO_PI * one_minus_cos_max);
  if (!(pdf > 0.0f) || isinf(pdf)) return invalid_light_sample();
  return LightSample(wi, dist, pdf, true);
}

// The pdf sample_sphere_light gives to the direction from p towards y, y a point where a ray
// from p met the sphere.
float sphere_light_pdf(vec3 p, vec3 center, float radius, vec3 y) {
  if (inside_sphere(p, center, radius)) return sphere_area_pdf(p, center, radius, y);
  float pdf = 1.0f / (TWO_PI * sphere_cone_one_minus_cos(radius, length(center - p)));
  return isinf(pdf) ? 0.0f : pdf;
}

// The solid-angle pdf of area sampling at point y of a plane with point v0 and unit normal,
// over the total area of the shape sampled in it (plane_point_pdf); quad_point_pdf takes the
// plane of a triangle with first vertex v0 and unnormalised normal m. The cosine at y is taken
// from the height of p above the plane, dot(n, v0 - p), not from y - p: y carries rounding of
// the corners' size, which swamps the height when p is almost in the plane.
float plane_point_pdf(vec3 p, vec3 v0, vec3 unit_normal, float total_area, vec3 y) {
  vec3 to_y = y - p;
  float dist2 = dot(to_y, to_y);
  float height = abs(dot(unit_normal, v0 - p));
  float cos_y = height * inversesqrt(dist2);
  if (!(dist2 > 0.0f) || !(cos_y > 0.0f) || !(total_area > 0.0f)) return 0.0f;
  return dist2 / (total_area * cos_y);
}

float quad_point_pdf(vec3 p, vec3 v0, vec3 m, float total_area, vec3 y) {
  return plane_point_pdf(p, v0, normalize(m), total_area, y);
}

// The quad (p0, p1, p2, p3) is the triangles (p0, p1, p2) and (p1, p3, p2) (docs/DESIGN.md §6): a
// triangle is chosen in proportion to its area, then a point uniformly inside it
// (b0 = 1 - sqrt(u0); Turk 1990). Emission leaves both sides.
LightSample sample_quad_light(vec3 p, vec3 p0, vec3 p1, vec3 p2, vec3 p3, vec2 u) {
  vec3 ma = cross(p1 - p0, p2 - p0);
  vec3 mb = cross(p3 - p1, p2 - p1);
  float area_a = 0.5f * length(ma);
  float area_b = 0.5f * length(mb);
  float total = area_a + area_b;
  if (!(total > 0.0f)) return invalid_light_sample();
  float fraction_a = area_a / total;
  vec3 v0 = p1;
  vec3 v1 = p3;
  vec3 v2 = p2;
  vec3 m = mb;
  float ux = u.x;
  if (ux < fraction_a) {
    v0 = p0;
    v1 = p1;
    m = ma;
    ux = ux / fraction_a;
  } else {
    ux = (ux - fraction_a) / (1.0f - fraction_a);
  }
  ux = min(ux, 1.0f);
  // Barycentrics (1 - sqrt(ux), sqrt(ux) (1 - u.y), sqrt(ux) u.y), as edge coordinates:
  float su = sqrt(ux);
  float b1 = su * (1.0f - u.y);
  float b2 = su * u.y;
  vec3 y = v0 + b1 * (v1 - v0) + b2 * (v2 - v0);
  vec3 to_y = y - p;
  float dist = length(to_y);
  float pdf = quad_point_pdf(p, v0, m, total, y);
  if (!(dist > 0.0f) || !(pdf > 0.0f) || isinf(pdf)) return invalid_light_sample();
  return LightSample(to_y / dist, dist, pdf, true);
}

// A parallelogram quad (p3 = p1 + p2 - p0, renderer/quad_shape.h) sampled by the affine map
// y = p0 + u.x (p1 - p0) + u.y (p2 - p0): uniform in area like sample_quad_light, so both have
// the same density and quad_light_pdf serves both. The map is affine: no triangle choice
// splitting u.x and no square-root warp squeezing cells towards a corner, so a stratified
// (Sobol') u stays stratified on the light (continuous maps of low distortion keep the
// strata's shape; Shirley and Chiu 1997, "A Low Distortion Map Between Disk and Square").
// Also cheaper: no choice, and the unit normal and the area come from the scene's tables
// (computed once, in double), so parallelogram_light_pdf can give the same pdf from the light
// table without the other corners.
LightSample sample_parallelogram_light(vec3 p, vec3 p0, vec3 p1, vec3 p2, vec3 unit_normal, float area,
                                       vec2 u) {
  if (!(area > 0.0f)) return invalid_light_sample();
  vec3 y = p0 + u.x * (p1 - p0) + u.y * (p2 - p0);
  vec3 to_y = y - p;
  float dist = length(to_y);
  float pdf = plane_point_pdf(p, p0, unit_normal, area, y);
  if (!(dist > 0.0f) || !(pdf > 0.0f) || isinf(pdf)) return invalid_light_sample();
  return LightSample(to_y / dist, dist, pdf, true);
}

// The pdf sample_parallelogram_light gives to the direction from p towards y, y a point on the
// parallelogram (a ray hit): quad_light_pdf's value, from p0, the unit normal and the area alone.
float parallelogram_light_pdf(vec3 p, vec3 p0, vec3 unit_normal, float area, vec3 y) {
  return plane_point_pdf(p, p0, unit_normal, area, y);
}

// The pdf sample_quad_light gives to the direction from p towards y, y a point on the quad
// (a ray hit). y lies on the triangle on its side of the shared diagonal p1-p2; the side is
// measured along the sum of the two triangles' normals, which is not parallel to the diagonal
// plane unless the quad is folded by 90 degrees or more.
float quad_light_pdf(vec3 p, vec3 p0, vec3 p1, vec3 p2, vec3 p3, vec3 y) {
  vec3 ma = cross(p1 - p0, p2 - p0);
  vec3 mb = cross(p3 - p1, p2 - p1);
  float total = 0.5f * length(ma) + 0.5f * length(mb);
  vec3 diagonal = p2 - p1;
  vec3 side_axis = normalize(ma) + normalize(mb);
  float side_y = dot(cross(diagonal, y - p1), side_axis);
  float side_p0 = dot(cross(diagonal, p0 - p1), side_axis);
  bool on_a = (side_y < 0.0f) == (side_p0 < 0.0f);
  return on_a ? quad_point_pdf(p, p0, ma, total, y) : quad_point_pdf(p, p1, mb, total, y);
}

// Veach's power heuristic (beta = 2) for a sample drawn from pdf_a: a^2 / (a^2 + b^2), written
// with the ratio of the smaller pdf to the larger so that huge pdfs (a point light seen through
// a tiny sphere: 1e15 and more) do not overflow when squared. A zero, negative or NaN pdf_a
// gives 0; pdf_a = inf with finite pdf_b gives 1; equal pdfs (inf included) give 1/2.
float power_heuristic(float pdf_a, float pdf_b) {
  if (!(pdf_a > 0.0f)) return 0.0f;
  if (!(pdf_b > 0.0f)) return 1.0f;
  if (pdf_a == pdf_b) return 0.5f;
  if (pdf_a > pdf_b) {
    float r = pdf_b / pdf_a;
    return 1.0f / (1.0f + r * r);
  }
  float r = pdf_a / pdf_b;
  float r2 = r * r;
  return r2 / (1.0f + r2);
}

#endif
