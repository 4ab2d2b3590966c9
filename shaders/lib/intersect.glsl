// Ray-primitive intersection for spheres and quads (two triangles).
#ifndef GLINT_INTERSECT_GLSL
#define GLINT_INTERSECT_GLSL

const float NO_HIT = -1.0f;

// The nearest t in (tmin, tmax) where the ray meets the sphere, or NO_HIT.
// Numerically careful form of Haines et al., "Precision Improvements for Ray/Sphere
// Intersection" (Ray Tracing Gems, ch. 7): the discriminant is computed from the distance
// of the centre to the ray line, not as the difference b^2 - ac of two large numbers, and the
// roots avoid cancellation by computing q first.
float intersect_sphere(Ray ray, vec3 center, float radius, float tmin, float tmax) {
  vec3 f = ray.origin - center;
  float a = dot(ray.direction, ray.direction);
  float b = dot(f, ray.direction);  // half the usual b
  vec3 closest = f - (b / a) * ray.direction;
  float discriminant = a * (radius * radius - dot(closest, closest));
  if (discriminant < 0.0f) return NO_HIT;
  float c = dot(f, f) - radius * radius;
  float q = -b - (b < 0.0f ? -1.0f : 1.0f) * sqrt(discriminant);
  float t0 = q != 0.0f ? c / q : 0.0f;
  float t1 = q / a;
  float near_t = min(t0, t1);
  float far_t = max(t0, t1);
  if (near_t > tmin && near_t < tmax) return near_t;
  if (far_t > tmin && far_t < tmax) return far_t;
  return NO_HIT;
}

// Moller-Trumbore. Returns (t, b1, b2) with the hit at (1-b1-b2) p0 + b1 p1 + b2 p2, or t =
// NO_HIT. Edges are inclusive so that two triangles sharing an edge leave no crack.
vec3 intersect_triangle(Ray ray, vec3 p0, vec3 p1, vec3 p2, float tmin, float tmax) {
  vec3 e1 = p1 - p0;
  vec3 e2 = p2 - p0;
  vec3 pvec = cross(ray.direction, e2);
  float det = dot(e1, pvec);
  if (det == 0.0f) return vec3(NO_HIT, 0.0f, 0.0f);
  float inv_det = 1.0f / det;
  vec3 tvec = ray.origin - p0;
  float b1 = dot(tvec, pvec) * inv_det;
  if (b1 < 0.0f || b1 > 1.0f) return vec3(NO_HIT, 0.0f, 0.0f);
  vec3 qvec = cross(tvec, e1);
  float b2 = dot(ray.direction, qvec) * inv_det;
  if (b2 < 0.0f || b1 + b2 > 1.0f) return vec3(NO_HIT, 0.0f, 0.0f);
  float t = dot(e2, qvec) * inv_det;
  if (!(t > tmin && t < tmax)) return vec3(NO_HIT, 0.0f, 0.0f);
  return vec3(t, b1, b2);
}

// A quad hit: t (NO_HIT on a miss) and the texture coordinates interpolated over the
// triangle that was hit.
struct QuadHit {
  float t;
  vec2 uv;
};

// The quad (p0, p1, p2, p3) is the triangles (p0, p1, p2) and (p1, p3, p2).
QuadHit intersect_quad(Ray ray, vec3 p0, vec3 p1, vec3 p2, vec3 p3, vec2 uv0, vec2 uv1,
                       vec2 uv2, vec2 uv3, float tmin, float tmax) {
  vec3 h = intersect_triangle(ray, p0, p1, p2, tmin, tmax);
  if (h.x != NO_HIT) return QuadHit(h.x, (1.0f - h.y - h.z) * uv0 + h.y * uv1 + h.z * uv2);
  h = intersect_triangle(ray, p1, p3, p2, tmin, tmax);
  if (h.x != NO_HIT) return QuadHit(h.x, (1.0f - h.y - h.z) * uv1 + h.y * uv3 + h.z * uv2);
  return QuadHit(NO_HIT, vec2(0.0f));
}

vec3 quad_normal(vec3 p0, vec3 p1, vec3 p2) { return normalize(cross(p1 - p0, p2 - p0)); }

#endif
