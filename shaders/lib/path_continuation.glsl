// A camera path in flight and one bounce of it: emission found, next-event estimation, the
// BSDF sample of the next ray and Russian roulette.
// GLSL only, part of the trace program (shaders/trace_common.glsl includes it after the
// shared maths); not compiled as C++ (renderer/shader_lib.h), since it reads the uniforms,
// tables and samplers of the trace program.

// A path in flight: what continue_path carries from one bounce to the next.
struct PathState {
  Ray ray;
  vec3 radiance;
  vec3 throughput;
  int bounces;
  int passes;  // pass-throughs of cut-outs so far (not bounces)
  // The last scattering vertex: where next-event estimation would have sampled the light that
  // a BSDF-sampled ray finds, for the MIS weight. Camera rays and delta lobes get weight 1.
  vec3 last_p;
  float last_pdf;
  bool last_delta;
  // The product of eta^2 over the refractions so far: a refracted ray's weight carries 1 / eta^2
  // (lib/dielectric.glsl), which the roulette undoes, so that a path inside glass is not killed
  // for a scale it loses again on the way out (pbrt-v4's etaScale; Mitsuba 3 does the same).
  float eta_scale;
#if defined(GLINT_MNEE)
  // Where the path stands in manifold next-event estimation's share of path space
  // (mnee_chain_state): MNEE_CHAIN_NONE outside it, else the state of the chain since the last
  // vertex at which MNEE ran; mnee_caster the sphere the chain is in.
  int mnee_chain;
  int mnee_caster;
  int mnee_vertices;  // vertices at which MNEE ran (at most MNEE_VERTICES, the first non-delta ones)
#endif
};

#if defined(GLINT_MNEE)
const int MNEE_CHAIN_NONE = 0;
const int MNEE_CHAIN_FROM_X = 1;  // the BSDF ray of a vertex at which MNEE ran
const int MNEE_CHAIN_INSIDE = 2;  // then refracted into caster mnee_caster
const int MNEE_CHAIN_DONE = 3;    // then reflected off a caster, or refracted out of it
const int MNEE_VERTICES = 2;
#endif

PathState start_path(Ray ray) {
#if defined(GLINT_MNEE)
  return PathState(ray, vec3(0.0), vec3(1.0), 0, 0, ray.origin, 0.0, true, 1.0, MNEE_CHAIN_NONE, -1, 0);
#else
  return PathState(ray, vec3(0.0), vec3(1.0), 0, 0, ray.origin, 0.0, true, 1.0);
#endif
}

#if defined(GLINT_MNEE)
// The chain state after scattering at `hit` into wi: MNEE counts
// exactly the paths that leave a vertex where it ran, reflect once off a caster from outside
// (mirror, glass or thin glass), or refract into a glass caster and straight out of the same
// one, and then meet an emitter or the environment map that it samples (lib/manifold_nee.glsl);
// the path tracer gives those weight 0. Cut-outs and smooth thin glass passed straight through
// (`straight`) are not vertices: MNEE's segments pass them too. Anything else on the way
// (another surface, an internal reflection) leaves the chain.
int mnee_chain_state(int state, inout int caster, bool mnee_ran, SceneHit hit, bool straight, vec3 wo, vec3 wi) {
  if (mnee_ran) return MNEE_CHAIN_FROM_X;
  if (straight) return state;
  bool outside = dot(hit.normal, wo) > 0.0;  // a sphere's normal points out
  bool leaves = dot(hit.normal, wi) > 0.0;
  if (state == MNEE_CHAIN_FROM_X && outside && mnee_is_caster(hit.ref)) {
    if (leaves) return MNEE_CHAIN_DONE;  // a reflection, off a mirror, glass or thin glass
    caster = hit.ref;
    return MNEE_CHAIN_INSIDE;
  }
  if (state == MNEE_CHAIN_INSIDE && hit.ref == caster && !outside && leaves) return MNEE_CHAIN_DONE;
  return MNEE_CHAIN_NONE;
}
#endif

// Whether next-event estimation has anything to sample: emitting shapes or an environment map.
bool light_sampling_on() {
#if defined(GLINT_NO_LIGHT_SAMPLING)
  return false;
#else
  return u_light_count > 0 || u_env_select > 0.0;
#endif
}

// One closest-hit query of the path and what follows from it: the emission or environment it
// finds, next-event estimation and the BSDF sample of the next ray. Returns false when the path
// has ended (its radiance is then final).
bool continue_path(inout PathState path) {
  bool light_sampling = light_sampling_on();
  Ray ray = path.ray;
  SceneHit hit = intersect_scene(ray);
  if (hit.material < 0) {
    float w = 1.0;
#if !defined(GLINT_NO_ENV_TEXTURE)  // without an environment map u_env_select is 0
    if (!path.last_delta && u_env_select > 0.0) {
      w = power_heuristic(path.last_pdf, u_env_select * environment_pdf(ray.direction, u_env_rotation));
    }
#endif
#if defined(GLINT_MNEE)
    // A caustic chain that manifold next-event estimation counts.
    if (path.mnee_chain == MNEE_CHAIN_DONE && mnee_samples_environment()) w = 0.0;
#endif
    if (path.bounces == 0) g_primary_escaped = true;
    if (!(u_transparent_background && path.bounces == 0))
      path.radiance += path.throughput * environment(ray.direction) * w;
    return false;
  }
  GpuMaterial gm = material_at(hit.material);
  vec3 p = hit.position;
  vec3 wo = -ray.direction;
  vec3 n = dot(hit.normal, wo) >= 0.0 ? hit.normal : -hit.normal;
  vec4 color_tex = texture_lookup(gm.layers.x, hit.uv);
#if !defined(GLINT_NO_COVERAGE)  // without it coverage is 1: no test, and no rand() either
  float coverage = gm.params.z * color_tex.a;
  if (coverage < 1.0 && path.passes < MAX_PASS_THROUGH && rand() >= coverage) {
    // Not a bounce: the ray continues unchanged past the surface.
    path.ray.origin = offset_surface_point(p, -n, hit.error_scale);
    ++path.passes;
    return true;
  }
#endif
#if !defined(GLINT_NO_EMITTERS)
  // Emission found by BSDF sampling, weighted against next-event estimation of the same
  // light from last_p. Shapes that are not lights (no estimated power) keep weight 1.
  float w = 1.0;
  if (hit.light >= 0 && !path.last_delta && u_light_count > 0) {
    w = power_heuristic(path.last_pdf, light_pdf(hit.light, path.last_p, p));
  }
#if defined(GLINT_MNEE)
  // A caustic chain that manifold next-event estimation counts.
  if (path.mnee_chain == MNEE_CHAIN_DONE && hit.light >= 0 && mnee_light_supported(light_at(hit.light))) w = 0.0;
#endif
  path.radiance += path.throughput * material_emission(gm, hit.uv) * w;
#endif
  if (path.bounces >= u_max_bounces) return false;
  SurfaceMaterial m = surface_material(gm, color_tex, hit.uv);
#if !defined(GLINT_NO_REFRACTIVE)
  // A refractive surface's inside is a sphere's ball and the side of a quad opposite its
  // geometric normal: a ray arriving from there leaves the material (relative index 1 / ior).
  if (m.type == MATERIAL_REFRACTIVE && dot(hit.normal, wo) < 0.0) m.ior = 1.0 / m.ior;
#endif
  bool delta = is_delta_material(m);
#if !defined(GLINT_NO_LIGHT_SAMPLING)
  if (light_sampling && !delta) {
    path.radiance += path.throughput * direct_light(m, p, n, wo, hit.error_scale, path.bounces);
  }
#endif
#if defined(GLINT_MNEE)
  // At the first MNEE_VERTICES non-delta vertices: the caustics seen directly (or through
  // smooth surfaces) and the light they throw on other surfaces; deeper ones are left to path
  // tracing (docs/DESIGN.md §3.10).
  bool mnee_ran = light_sampling && !delta && path.mnee_vertices < MNEE_VERTICES && mnee_on() && mnee_receiver(m);
  if (mnee_ran) ++path.mnee_vertices;
  if (mnee_ran) path.radiance += path.throughput * manifold_next_event(m, p, n, wo, hit.error_scale, path.bounces);
#endif
  float u_lobe = sample_1d(bsdf_dimension(path.bounces));
  vec2 u = sample_2d(bsdf_dimension(path.bounces));
  BsdfSample s = sample_bsdf(m, n, wo, u_lobe, u);
  if (!s.valid) return false;
#if defined(GLINT_MNEE)
  bool straight = s.delta && dot(s.wi, n) < 0.0 && m.type == MATERIAL_TRANSPARENT;  // thin glass passed
  path.mnee_chain = mnee_chain_state(path.mnee_chain, path.mnee_caster, mnee_ran, hit, straight, wo, s.wi);
#endif
  path.throughput *= s.weight;
  if (max_component(path.throughput) <= 0.0) return false;
  // Smooth thin glass passing a ray straight on is not a new vertex for MIS: the light it
  // finds is the one next-event estimation at last_p aimed at, along the same direction.
  // (A refractive surface bends the ray and blocks shadow rays: its delta lobes are vertices
  // with last_delta, so the light they find has weight 1.)
  path.ray = Ray(offset_surface_point(p, dot(s.wi, n) > 0.0 ? n : -n, hit.error_scale), s.wi);
#if !defined(GLINT_NO_REFRACTIVE)
  if (m.type == MATERIAL_REFRACTIVE && dot(s.wi, n) < 0.0) path.eta_scale *= m.ior * m.ior;
#endif
  if (!(s.delta && dot(s.wi, n) < 0.0 && m.type == MATERIAL_TRANSPARENT)) {
    path.last_p = path.ray.origin;
    path.last_pdf = s.pdf;
    path.last_delta = s.delta;
  }
  ++path.bounces;
  if (u_russian_roulette && path.bounces >= ROULETTE_START) {
    // Survive with probability max(throughput) eta_scale (at most 1); survivors carry 1/q more.
    float q = min(1.0, max_component(path.throughput) * path.eta_scale);
    if (rand() >= q) return false;
    path.throughput /= q;
  }
  return true;
}
