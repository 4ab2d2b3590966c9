// Next-event estimation: picking a light, sampling a point on it, the shadow ray and the
// MIS-weighted direct light at a non-delta vertex (power heuristic, Veach 1997 ch. 9).
// GLSL only, part of the trace program (shaders/trace_common.glsl includes it after the
// shared maths); not compiled as C++ (renderer/shader_lib.h), since it reads the uniforms,
// tables and samplers of the trace program.

// The solid-angle pdf with which next-event estimation at p picks the point y of light i.
float light_pdf(int i, vec3 p, vec3 y) {
  GpuLight l = light_at(i);
  float shape_pdf = 0.0;
#if !defined(GLINT_NO_SPHERES)
  if (l.shape.x == 0) {
    vec4 s = sphere_at(l.shape.y).center_radius;
    shape_pdf = sphere_light_pdf(p, s.xyz, s.w, y);
  }
#endif
#if !defined(GLINT_NO_QUADS)
  if (l.shape.x != 0) {
    GpuQuad q = quad_at(l.shape.y);  // only the texels read are fetched
#if !defined(GLINT_NO_GENERAL_QUAD_LIGHTS)
    if (l.shape.z == 0) shape_pdf = quad_light_pdf(p, q.p0.xyz, q.p1.xyz, q.p2.xyz, q.p3.xyz, y);
    else
#endif
      shape_pdf = parallelogram_light_pdf(p, q.p0.xyz, q.normal.xyz, l.select.z, y);
  }
#endif
  return (1.0 - u_env_select) * l.select.x * shape_pdf;
}

// The light whose cdf interval holds u (binary search: scenes may hold many emitters).
int pick_light(float u) {
  int lo = 0;
  int hi = u_light_count - 1;
  while (lo < hi) {
    int mid = (lo + hi) / 2;
    if (u < light_at(mid).select.y) hi = mid;
    else lo = mid + 1;
  }
  return lo;
}

// The material of primitive `ref` of a closest hit: x its index, y its light's (-1: none).
ivec4 primitive_material(int ref) {
#if !defined(GLINT_NO_QUADS) && !defined(GLINT_NO_SPHERES)
  return ref >= u_sphere_count ? quad_at(ref - u_sphere_count).material : sphere_at(ref).material;
#elif !defined(GLINT_NO_QUADS)
  return quad_at(ref - u_sphere_count).material;
#else
  return sphere_at(ref).material;
#endif
}

#if defined(GLINT_NO_COVERAGE) && defined(GLINT_NO_TRANSPARENT)
// Radiance reaching `origin` along wi from light `target` (-1: the environment) in a scene
// where every surface blocks light (refractive ones too): the first surface met decides. The
// general loop below gives the same value here, but llvmpipe runs every branch of it whether a
// pixel takes it or not. Without textures only which primitive was hit matters, not where, so
// the hit record (point, normal, uv) is not built either.
vec3 shadow_ray(vec3 origin, vec3 wi, int target) {
  Ray ray = Ray(origin, wi);
#if defined(GLINT_NO_TEXTURES)
  PrimitiveHit closest = closest_primitive(ray);
  if (closest.ref < 0) return target < 0 ? environment(wi) : vec3(0.0);
  ivec4 material = primitive_material(closest.ref);
  if (target < 0 || material.y != target) return vec3(0.0);
  return material_at(material.x).emission.rgb;
#else
  SceneHit hit = intersect_scene(ray);
  if (hit.material < 0) return target < 0 ? environment(wi) : vec3(0.0);
  if (target < 0 || hit.light != target) return vec3(0.0);
  return material_emission(material_at(hit.material), hit.uv);
#endif
}
#else
// Radiance reaching `origin` along wi from light `target` (-1: the environment), through
// cut-outs and smooth thin glass; 0 when anything else blocks it.
vec3 shadow_ray(vec3 origin, vec3 wi, int target) {
  Ray ray = Ray(origin, wi);
  vec3 transmittance = vec3(1.0);
  for (int passes = 0; passes <= MAX_PASS_THROUGH; ++passes) {
    SceneHit hit = intersect_scene(ray);
    if (hit.material < 0) return target < 0 ? transmittance * environment(wi) : vec3(0.0);
    GpuMaterial gm = material_at(hit.material);
    vec4 color_tex = texture_lookup(gm.layers.x, hit.uv);
    float coverage = gm.params.z * color_tex.a;
#if !defined(GLINT_NO_EMITTERS)
    if (target >= 0 && hit.light == target) {
      return transmittance * coverage * material_emission(gm, hit.uv);
    }
#endif
    vec3 n = dot(hit.normal, wi) <= 0.0 ? hit.normal : -hit.normal;  // towards the ray's origin
    transmittance *= straight_transmittance(gm, color_tex, hit.uv, coverage, dot(n, -wi));
    if (max_component(transmittance) <= 0.0) break;
    ray.origin = offset_surface_point(hit.position, -n, hit.error_scale);
  }
  return vec3(0.0);
}
#endif

// A light sample seen from `origin`: the point the shadow ray actually starts from.
LightSample sample_light(int i, vec3 origin, vec2 u) {
  GpuLight l = light_at(i);
#if !defined(GLINT_NO_SPHERES) || defined(GLINT_NO_QUADS)  // (with neither shape, never called)
#if !defined(GLINT_NO_QUADS)
  if (l.shape.x == 0)
#endif
  {
    vec4 s = sphere_at(l.shape.y).center_radius;
    return sample_sphere_light(origin, s.xyz, s.w, u);
  }
#endif
#if !defined(GLINT_NO_QUADS)
  GpuQuad q = quad_at(l.shape.y);
#if !defined(GLINT_NO_GENERAL_QUAD_LIGHTS)
  if (l.shape.z == 0) return sample_quad_light(origin, q.p0.xyz, q.p1.xyz, q.p2.xyz, q.p3.xyz, u);
#endif
  return sample_parallelogram_light(origin, q.p0.xyz, q.p1.xyz, q.p2.xyz, q.normal.xyz, l.select.z, u);
#endif
}

// One light sample at a non-delta vertex, weighted against BSDF sampling (power heuristic;
// Veach 1997, ch. 9). Returns f |cos| Li w / pdf. The light is sampled from the offset origin
// of the shadow ray, not from p: on shapes far from the origin the offset is large (16 float
// epsilons of 1e5 is 0.19), and a direction chosen from p but traced from the offset point
// would miss the edges of the light it aimed at (biased). BSDF rays record the same origin
// (last_p in continue_path), so both strategies see the light from the same point.
vec3 direct_light(SurfaceMaterial m, vec3 p, vec3 n, vec3 wo, float error_scale, int bounce) {
  float u_pick = sample_1d(light_dimension(bounce));
  vec2 u = sample_2d(light_dimension(bounce));
  vec3 above = offset_surface_point(p, n, error_scale);
  vec3 wi;
  float pdf;
  int target;
  vec3 origin = above;
#if !defined(GLINT_NO_ENV_TEXTURE)
  if (u_pick < u_env_select) {
    EnvironmentSample es = sample_environment(u, u_env_rotation);
    if (!es.valid || !(es.pdf > 0.0)) return vec3(0.0);
    wi = es.wi;
    pdf = u_env_select * es.pdf;
    target = -1;
    if (dot(wi, n) <= 0.0) origin = offset_surface_point(p, -n, error_scale);
  }
#endif
#if !defined(GLINT_NO_EMITTERS) && !defined(GLINT_NO_ENV_TEXTURE)
  else
#endif
#if !defined(GLINT_NO_EMITTERS)
  {
    target = pick_light((u_pick - u_env_select) / (1.0 - u_env_select));
    LightSample ls = sample_light(target, above, u);
    if ((m.type == MATERIAL_TRANSPARENT || m.type == MATERIAL_REFRACTIVE) && ls.valid && dot(ls.wi, n) <= 0.0) {
      // Rough glass also transmits: the light is below, seen from below.
      origin = offset_surface_point(p, -n, error_scale);
      ls = sample_light(target, origin, u);
      if (dot(ls.wi, n) >= 0.0) return vec3(0.0);
    }
    if (!ls.valid) return vec3(0.0);
    wi = ls.wi;
    pdf = (1.0 - u_env_select) * light_at(target).select.x * ls.pdf;
  }
#endif
  vec3 f = eval_bsdf(m, n, wo, wi);
  if (max_component(f) <= 0.0) return vec3(0.0);
  vec3 li = shadow_ray(origin, wi, target);
  if (max_component(li) <= 0.0) return vec3(0.0);
  return f * li * (power_heuristic(pdf, pdf_bsdf(m, n, wo, wi)) / pdf);
}
