// Closest hits against the scene (loop, unrolled loop or BVH) and the hit record a bounce
// needs: point, normal, uv, material, light.
// GLSL only, part of the trace program (shaders/trace_common.glsl includes it after the
// shared maths); not compiled as C++ (renderer/shader_lib.h), since it reads the uniforms,
// tables and samplers of the trace program.

struct SceneHit {
  float t;
  vec3 position;  // on the surface to a few ulps of error_scale (not o + t d)
  float error_scale;  // coordinate magnitude of the shape (see surface_offset_distance)
  vec3 normal;  // geometric, unit, not yet flipped
  vec2 uv;
  int material;
  int light;  // index into lights[] when the shape emits, else -1
  int ref;    // the primitive (PrimitiveHit::ref: spheres, then quads), -1 for none
};

// The scene as shaders/lib/bvh.glsl reads it.
int scene_sphere_count() { return u_sphere_count; }
int scene_quad_count() { return u_quad_count; }
// The nearest hit in (0, tmax) of a sphere or a quad, or NO_HIT (every ray the tracer spawns has
// a unit direction).
float sphere_hit(vec4 center_radius, Ray ray, float tmax) {
  return intersect_unit_sphere(ray, center_radius.xyz, center_radius.w, 0.0, tmax);
}
float quad_hit(GpuQuad q, Ray ray, float tmax) {
#if defined(GLINT_NO_GENERAL_QUADS)
  // Every quad is planar and convex: intersect_planar_quad's two steps.
  float t = planar_quad_plane_t(ray, q.p0.xyz, q.normal.xyz, 0.0, tmax);
  if (t == NO_HIT) return NO_HIT;
  if (!planar_quad_inside_edges(ray, q.p0.xyz, q.p1.xyz, q.p2.xyz, q.p3.xyz)) return NO_HIT;
  return t;
#else
  return intersect_quad(ray, q.p0.xyz, q.p1.xyz, q.p2.xyz, q.p3.xyz, q.uv01.xy, q.uv01.zw,
                        q.uv23.xy, q.uv23.zw, 0.0, tmax).t;
#endif
}
float scene_sphere_hit(int i, Ray ray, float tmax) {
  return sphere_hit(sphere_at(i).center_radius, ray, tmax);
}
float scene_quad_hit(int i, Ray ray, float tmax) { return quad_hit(quad_at(i), ray, tmax); }
#if defined(GLINT_LOOP_SPHERES)
#include "unrolled_loop.glsl"
#endif
BvhNode bvh_node(int i) {
  ivec4 a = table_texel(u_bvh_node_table, 2 * i);
  ivec4 b = table_texel(u_bvh_node_table, 2 * i + 1);
  return BvhNode(intBitsToFloat(a.xyz), a.w, intBitsToFloat(b.xyz), b.w);
}
int bvh_primitive(int i) { return table_texel(u_bvh_primitive_table, i).x; }

// Set when this sample's camera ray found the environment (after any cut-outs it passed).
bool g_primary_escaped;
// Set when a BVH traversal of this sample stopped at its step cap: the sample is discarded
// (counted with the non-finite ones) rather than added with a possibly wrong hit.
bool g_incomplete;

PrimitiveHit closest_primitive(Ray ray) {
#if defined(GLINT_LOOP_SPHERES)
  return closest_hit_unrolled(ray, 1e30);
#elif defined(GLINT_NO_BVH)
  return closest_hit_loop(ray, 1e30);
#else
#if !defined(GLINT_NO_LOOP)
  if (!u_use_bvh) return closest_hit_loop(ray, 1e30);
#endif
  PrimitiveHit h = closest_hit_bvh(ray, 1e30, u_bvh_max_steps);
  if (!h.complete) g_incomplete = true;
  return h;
#endif
}

SceneHit intersect_scene(Ray ray) {
  SceneHit hit = SceneHit(1e30, vec3(0.0), 0.0, vec3(0.0), vec2(0.0), -1, -1, -1);
  PrimitiveHit closest = closest_primitive(ray);
  if (closest.ref < 0) return hit;
  hit.t = closest.t;
  hit.ref = closest.ref;
#if !defined(GLINT_NO_QUADS)
#if !defined(GLINT_NO_SPHERES)
  if (closest.ref >= u_sphere_count)
#endif
  {
    GpuQuad q = quad_at(closest.ref - u_sphere_count);
    // The quad's nearest hit again, for its texture coordinates and point (the same t: the
    // test's result does not depend on tmax beyond it).
    QuadHit h = intersect_quad(ray, q.p0.xyz, q.p1.xyz, q.p2.xyz, q.p3.xyz, q.uv01.xy, q.uv01.zw,
                               q.uv23.xy, q.uv23.zw, 0.0, 1e30);
    hit.uv = h.uv;
    hit.position = h.t != NO_HIT ? h.position : ray.origin + hit.t * ray.direction;
    hit.normal = q.normal.xyz;
    hit.error_scale = quad_error_scale(q.p0.xyz, q.p1.xyz, q.p2.xyz, q.p3.xyz);
    hit.material = q.material.x;
    hit.light = q.material.y;
  }
#endif
#if !defined(GLINT_NO_QUADS) && !defined(GLINT_NO_SPHERES)
  else
#endif
#if !defined(GLINT_NO_SPHERES)
  {
    GpuSphere sphere = sphere_at(closest.ref);
    vec4 s = sphere.center_radius;
    hit.position = sphere_hit_point(ray, hit.t, s.xyz, s.w);
    hit.error_scale = sphere_error_scale(s.xyz, s.w);
    hit.normal = normalize(hit.position - s.xyz);
    hit.uv = direction_to_uv(hit.normal);
    hit.material = sphere.material.x;
    hit.light = sphere.material.y;
  }
#endif
  return hit;
}
