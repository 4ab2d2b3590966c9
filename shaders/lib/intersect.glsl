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

// intersect_sphere for a unit direction (|d| = 1 to a few ulps, as every ray the tracer spawns
// is): with a = 1 the three divisions by a and the dot product for it drop out, leaving c / q.
// The direction's rounding (|d|^2 = 1 + e, e a few ulps) scales t by about 1 - e / 2, within the
// rounding t carries anyway.
float intersect_unit_sphere(Ray ray, vec3 center, float radius, float tmin, float tmax) {
  vec3 f = ray.origin - center;
  float b = dot(f, ray.direction);  // half the usual b
  vec3 closest = f - b * ray.direction;
  float discriminant = radius * radius - dot(closest, closest);
  if (discriminant < 0.0f) return NO_HIT;
  float c = dot(f, f) - radius * radius;
  float q = -b - (b < 0.0f ? -1.0f : 1.0f) * sqrt(discriminant);
  float t0 = q != 0.0f ? c / q : 0.0f;
  float near_t = min(t0, q);
  float far_t = max(t0, q);
  if (near_t > tmin && near_t < tmax) return near_t;
  if (far_t > tmin && far_t < tmax) return far_t;
  return NO_HIT;
}

// The hit point of a sphere hit at t, put back onto the sphere: o + t d carries the rounding of
// t times |d| (t can be 1e4 radii for a far camera, and t itself is only known to ulps of
// |o - c|), while the reprojected point is within a few ulps of |c| + r of the surface.
vec3 sphere_hit_point(Ray ray, float t, vec3 center, float radius) {
  vec3 p = ray.origin + t * ray.direction;
  return center + radius * normalize(p - center);
}

// The coordinate magnitude that bounds the rounding of a sphere's surface points: the
// reprojected point rounds at ulps of r (r times a unit vector) and of |c| (the sum).
float sphere_error_scale(vec3 center, float radius) {
  return max(max_component(abs(center)), radius);
}

// The same for a quad: its largest corner coordinate.
float quad_error_scale(vec3 p0, vec3 p1, vec3 p2, vec3 p3) {
  return max(max(max_component(abs(p0)), max_component(abs(p1))),
             max(max_component(abs(p2)), max_component(abs(p3))));
}

// Triangles are tested with signed volumes (the ray's side of each edge, as in Woop et al.,
// "Watertight Ray/Triangle Intersection", JCGT 2013): edge_volume(d, a, b) with a, b the edge's
// endpoints relative to the ray origin. Swapping the endpoints negates it exactly (same
// products, subtraction reversed), so two triangles sharing an edge get the same value with
// opposite signs; with inclusive edges every ray crossing the edge hits one of them.
// (Moller-Trumbore rounds each triangle's barycentrics separately: about 12% of rays aimed
// exactly at a quad's diagonal missed both of its triangles.)
float edge_volume(vec3 d, vec3 a, vec3 b) { return dot(d, cross(a, b)); }

// The hit of the triangle whose edge opposite vertex i has volume wi, given a = p0 - origin and
// the triangle's normal n = cross(p1 - p0, p2 - p0): (t, b1, b2) or t = NO_HIT.
vec3 triangle_hit(vec3 d, vec3 a, vec3 n, float w0, float w1, float w2, float tmin, float tmax) {
  if ((w0 < 0.0f || w1 < 0.0f || w2 < 0.0f) && (w0 > 0.0f || w1 > 0.0f || w2 > 0.0f)) {
    return vec3(NO_HIT, 0.0f, 0.0f);
  }
  float det = w0 + w1 + w2;  // = dot(d, n) up to rounding
  if (det == 0.0f) return vec3(NO_HIT, 0.0f, 0.0f);
  float t = dot(a, n) / dot(d, n);
  if (!(t > tmin && t < tmax)) return vec3(NO_HIT, 0.0f, 0.0f);
  return vec3(t, w1 / det, w2 / det);
}

// Returns (t, b1, b2) with the hit at (1-b1-b2) p0 + b1 p1 + b2 p2, or t = NO_HIT. Both sides
// hit; edges are inclusive.
vec3 intersect_triangle(Ray ray, vec3 p0, vec3 p1, vec3 p2, float tmin, float tmax) {
  vec3 d = ray.direction;
  vec3 a = p0 - ray.origin;
  vec3 b = p1 - ray.origin;
  vec3 c = p2 - ray.origin;
  return triangle_hit(d, a, cross(p1 - p0, p2 - p0), edge_volume(d, b, c), edge_volume(d, c, a),
                      edge_volume(d, a, b), tmin, tmax);
}

// A quad hit: t (NO_HIT on a miss), the texture coordinates interpolated over the triangle
// that was hit, and the hit point from the barycentrics (p0 + b1 e1 + b2 e2): its rounding is
// a few ulps of the corners, whatever the ray's origin and length (o + t d is off the plane
// by the rounding of t, eps t, which grows with the camera's distance).
struct QuadHit {
  float t;
  vec2 uv;
  vec3 position;
};

// The quad (p0, p1, p2, p3) is the triangles (p0, p1, p2) and (p1, p3, p2). The volume of the
// shared diagonal p1-p2 is computed once and used (negated) by both triangles, so no ray
// crosses between them even where the compiler fuses multiply-adds. Non-planar quads can be
// hit twice; the nearer hit wins.
QuadHit intersect_quad(Ray ray, vec3 p0, vec3 p1, vec3 p2, vec3 p3, vec2 uv0, vec2 uv1,
                       vec2 uv2, vec2 uv3, float tmin, float tmax) {
  vec3 d = ray.direction;
  vec3 a0 = p0 - ray.origin;
  vec3 a1 = p1 - ray.origin;
  vec3 a2 = p2 - ray.origin;
  vec3 a3 = p3 - ray.origin;
  float diagonal = edge_volume(d, a1, a2);
  QuadHit hit = QuadHit(NO_HIT, vec2(0.0f), vec3(0.0f));
  vec3 h = triangle_hit(d, a0, cross(p1 - p0, p2 - p0), diagonal, edge_volume(d, a2, a0),
                        edge_volume(d, a0, a1), tmin, tmax);
  if (h.x != NO_HIT) {
    hit = QuadHit(h.x, (1.0f - h.y - h.z) * uv0 + h.y * uv1 + h.z * uv2,
                  p0 + h.y * (p1 - p0) + h.z * (p2 - p0));
    tmax = h.x;
  }
  h = triangle_hit(d, a1, cross(p3 - p1, p2 - p1), edge_volume(d, a3, a2), -diagonal,
                   edge_volume(d, a1, a3), tmin, tmax);
  if (h.x != NO_HIT) {
    hit = QuadHit(h.x, (1.0f - h.y - h.z) * uv1 + h.y * uv3 + h.z * uv2,
                  p1 + h.y * (p3 - p1) + h.z * (p2 - p1));
  }
  return hit;
}

// A planar convex quad, the cheaper test for scenes whose quads all are (renderer/quad_shape.h
// decides, within a rounding small against the ray offset of common.glsl), in two steps: the
// plane's t (`normal`: any non-zero normal of the plane; NO_HIT outside (tmin, tmax), also for
// a ray parallel to it), then whether the ray passes inside the four boundary edges. The edge
// volumes are the same edge_volume calls (same endpoints, same order) as intersect_quad's, so
// two quads sharing an edge still leave no crack, and a ray meets a convex quad iff the four
// have one sign (Woop et al. 2013; inclusive edges). The second step runs only for a t in range.
float planar_quad_plane_t(Ray ray, vec3 p0, vec3 normal, float tmin, float tmax) {
  float t = dot(p0 - ray.origin, normal) / dot(ray.direction, normal);
  return t > tmin && t < tmax ? t : NO_HIT;
}

bool planar_quad_inside_edges(Ray ray, vec3 p0, vec3 p1, vec3 p2, vec3 p3) {
  vec3 d = ray.direction;
  vec3 a0 = p0 - ray.origin;
  vec3 a1 = p1 - ray.origin;
  vec3 a2 = p2 - ray.origin;
  vec3 a3 = p3 - ray.origin;
  float w01 = edge_volume(d, a0, a1);
  float w13 = edge_volume(d, a1, a3);
  float w32 = edge_volume(d, a3, a2);
  float w20 = edge_volume(d, a2, a0);
  bool negative = w01 < 0.0f || w13 < 0.0f || w32 < 0.0f || w20 < 0.0f;
  bool positive = w01 > 0.0f || w13 > 0.0f || w32 > 0.0f || w20 > 0.0f;
  return !(negative && positive);
}

// Both steps: the nearest t in (tmin, tmax) where the ray meets the planar convex quad, or NO_HIT.
float intersect_planar_quad(Ray ray, vec3 p0, vec3 p1, vec3 p2, vec3 p3, vec3 normal, float tmin,
                            float tmax) {
  float t = planar_quad_plane_t(ray, p0, normal, tmin, tmax);
  if (t == NO_HIT || !planar_quad_inside_edges(ray, p0, p1, p2, p3)) return NO_HIT;
  return t;
}

vec3 quad_normal(vec3 p0, vec3 p1, vec3 p2) { return normalize(cross(p1 - p0, p2 - p0)); }

#endif
