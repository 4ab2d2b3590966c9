// Manifold next-event estimation (MNEE; Hanika, Droske and Fascione 2015, "Manifold Next Event
// Estimation") for chains through one smooth sphere: light that leaves a point y of an emitter,
// or arrives from a direction of the environment map, reflects off a smooth mirror, glass or
// thin-glass ball or refracts through a smooth glass ball (in, straight through, out) and
// reaches a non-delta vertex x (caustics, E D S L and E D S S L). The chains are found by
// symmetry (docs/DESIGN.md §3.10): {y, the sphere's centre, its radius} is symmetric about the
// axis through y and the centre (for the environment, the line through the centre along the
// light's direction), so every chain to x lies in the plane through that axis and x and is a
// ray from y at a signed angle t from the axis (parallel light: the ray along the axis at a
// signed distance t from it). The 1-D residual g(t) (x's distance from the chain's outgoing
// ray) is scanned on a grid and each sign change refined, so that every chain is found except
// root pairs closer than the grid spacing (at a caustic's fold). General MNEE solves from one
// seed and misses the other chains where several exist (Zeltner, Georgiev and Jakob 2020,
// "Specular Manifold Sampling").
// The paths counted here are given weight 0 in the path tracer (path_continuation.glsl,
// mnee_chain_state): a partition of path space (Veach 1997, ch. 10.3), no MIS weight needed.
// GLSL only, part of the trace program when renderer/shader_features.cpp defines GLINT_MNEE.

const int MNEE_MAX_CASTERS = 8;  // renderer/mnee_casters.h, kMaxMneeCasters
uniform int u_caster_count;      // casters: smooth mirror, glass or thin-glass spheres (indices)
uniform int u_casters[MNEE_MAX_CASTERS];
// Which lights MNEE samples (renderer/mnee_casters.h, mnee_lights): lamps, the environment map.
uniform int u_mnee_lights;
const int MNEE_LAMPS = 1;
const int MNEE_ENVIRONMENT = 2;
// Grid points of the scan over t and secant steps per root (docs/DESIGN.md §3.10 measures
// what a coarser grid misses).
const int MNEE_GRID = 32;
const int MNEE_REFINE_STEPS = 20;

bool mnee_samples_lamps() { return (u_mnee_lights & MNEE_LAMPS) != 0 && u_light_count > 0; }

bool mnee_samples_environment() {
#if defined(GLINT_NO_ENV_TEXTURE)
  return false;
#else
  return (u_mnee_lights & MNEE_ENVIRONMENT) != 0 && u_env_select > 0.0;
#endif
}

bool mnee_on() { return u_caster_count > 0 && (mnee_samples_lamps() || mnee_samples_environment()); }

// The probability that a sample of MNEE goes to the environment rather than to a lamp.
float mnee_environment_select() {
  if (!mnee_samples_environment()) return 0.0;
  return mnee_samples_lamps() ? u_env_select : 1.0;
}

// Whether MNEE runs at a vertex of material m: where its BSDF is broad. On a sharp lobe (a
// glossy coat or rough metal of low roughness) f at the chain's direction is mostly near 0 and
// now and then huge, and MNEE's estimate of the caustic has fireflies that BSDF sampling, which
// follows the lobe, does not have; the path tracer keeps those chains there. The coat's peak
// D = 1 / (pi alpha^2) times its F0 of 0.04 stays near the base's 1 / pi from roughness 0.25 on;
// a metal's F is near 1, so it needs a broader lobe.
const float MNEE_MIN_GLOSSY_ROUGHNESS = 0.25;
const float MNEE_MIN_ROUGHNESS = 0.5;
bool mnee_receiver(SurfaceMaterial m) {
  if (m.type == MATERIAL_MATTE) return true;
  return m.roughness >= (m.type == MATERIAL_GLOSSY ? MNEE_MIN_GLOSSY_ROUGHNESS : MNEE_MIN_ROUGHNESS);
}

// Lamps whose points MNEE samples: spheres and parallelogram quads (uniform in area).
bool mnee_light_supported(GpuLight l) { return mnee_samples_lamps() && (l.shape.x == 0 || l.shape.z == 1); }

// A caster sphere (renderer/gpu_scene.cpp marks it with material.z = 1).
bool mnee_is_caster(int ref) { return ref >= 0 && ref < u_sphere_count && sphere_at(ref).material.z == 1; }

// The meridional plane of y, the centre and x: origin y, `axis` towards the centre (at
// (dist, 0)), `side` towards x (at x2, x2.y >= 0). For parallel light (from the environment)
// the axis is the light's direction of travel and y a point on it before the sphere.
struct Meridian {
  vec3 y;
  vec3 axis;
  vec3 side;
  float dist;
  float radius;
  vec2 x2;
  bool parallel;
};

// One chain in the plane: the first hit p1, the last hit (p1 for a mirror, the exit for glass)
// and the outgoing direction; valid when it leaves towards x (x ahead of p_last).
struct Chain2D {
  vec2 p1;
  vec2 p_last;
  vec2 d_out;
  bool valid;
};

// Snell's law in the plane: d arriving against the unit normal n, eta = far index / near index.
vec2 refract_2d(vec2 d, vec2 n, float eta) {
  float cos_i = -dot(d, n);
  float k = 1.0 - (1.0 - cos_i) * (1.0 + cos_i) / (eta * eta);
  if (k < 0.0) return vec2(0.0);
  return d / eta + (cos_i / eta - sqrt(k)) * n;
}

// The chain of the ray from `origin` along the unit direction dir.
Chain2D mnee_chain_along(Meridian m, vec2 origin, vec2 dir, bool glass, float ior) {
  Chain2D c = Chain2D(vec2(0.0), vec2(0.0), vec2(1.0, 0.0), false);
  vec2 center = vec2(m.dist, 0.0);
  vec2 to_center = center - origin;
  float s = to_center.x * dir.y - to_center.y * dir.x;  // the centre's distance from the ray
  float h2 = (m.radius - s) * (m.radius + s);
  if (!(h2 >= 0.0)) return c;
  float t1 = dot(to_center, dir) - sqrt(h2);
  if (!(t1 > 0.0)) return c;
  c.p1 = origin + t1 * dir;
  vec2 n1 = (c.p1 - center) / m.radius;
  if (glass) {
    vec2 d1 = refract_2d(dir, n1, ior);  // (unit, as refract_2d keeps the length)
    c.p_last = c.p1 - 2.0 * dot(d1, c.p1 - center) * d1;  // the chord's far end
    vec2 d2 = refract_2d(d1, (center - c.p_last) / m.radius, 1.0 / ior);
    if (dot(d2, d2) == 0.0) return c;  // (no total internal reflection in a sphere)
    c.d_out = d2;
  } else {
    c.p_last = c.p1;
    c.d_out = reflect(dir, n1);
  }
  c.valid = dot(c.d_out, m.x2 - c.p_last) > 0.0;
  return c;
}

// The scan's ray at parameter t: from y at the angle t from the axis, or (parallel light)
// along the axis at the signed distance t from it.
vec2 mnee_ray_origin(Meridian m, float t) { return m.parallel ? vec2(0.0, t) : vec2(0.0); }
vec2 mnee_ray_direction(Meridian m, float t) { return m.parallel ? vec2(1.0, 0.0) : vec2(cos(t), sin(t)); }

Chain2D mnee_chain(Meridian m, float t, bool glass, float ior) {
  return mnee_chain_along(m, mnee_ray_origin(m, t), mnee_ray_direction(m, t), glass, ior);
}

// Signed distance of x from the chain's outgoing ray: 0 where the chain reaches x.
float mnee_residual(Meridian m, Chain2D c) {
  vec2 r = m.x2 - c.p_last;
  return c.d_out.x * r.y - c.d_out.y * r.x;
}

// The chain's outgoing ray met with x's tangent plane, relative to x (in 3-D).
vec3 mnee_plane_offset(Meridian m, Chain2D c, vec3 n) {
  vec2 q2 = c.p_last - m.x2;
  vec3 q = q2.x * m.axis + q2.y * m.side;
  vec3 d = c.d_out.x * m.axis + c.d_out.y * m.side;
  return q - d * (dot(q, n) / dot(d, n));
}

// dω_y / dA_x of the ray tube at a chain through x: the sagittal spread follows from the
// rotation about the axis, the meridional one from t (central difference; one-sided where a
// neighbour's ray misses the ball, at a grazing root); dω_y = |sin t| dt dpsi at y, dA_x =
// |d_m x d_s| dt dpsi on x's tangent plane. For parallel light dA_perp / dA_x, the beam's
// cross-section dA_perp = |t| dt dpsi.
float mnee_jacobian(Meridian m, float t, float h, Chain2D c, vec3 n, bool glass, float ior) {
  Chain2D lo = mnee_chain(m, t - h, glass, ior);
  Chain2D hi = mnee_chain(m, t + h, glass, ior);
  if (!lo.valid && !hi.valid) return 0.0;
  vec3 at_lo = lo.valid ? mnee_plane_offset(m, lo, n) : mnee_plane_offset(m, c, n);
  vec3 at_hi = hi.valid ? mnee_plane_offset(m, hi, n) : mnee_plane_offset(m, c, n);
  vec3 d_m = (at_hi - at_lo) / ((lo.valid && hi.valid ? 2.0 : 1.0) * h);
  vec3 d = c.d_out.x * m.axis + c.d_out.y * m.side;
  vec3 e_psi = cross(m.axis, m.side);
  float rho = m.x2.y;
  vec3 d_s = rho * e_psi - rho * (dot(e_psi, n) / dot(d, n)) * d;
  float area = length(cross(d_m, d_s));
  if (!(area > 0.0)) return 0.0;
  return (m.parallel ? abs(t) : abs(sin(t))) / area;
}

// A point of light i uniform in area: its position, normal and area.
struct MneeLightPoint {
  vec3 y;
  vec3 normal;
  float area;
  int ref;  // primitive reference of the light's shape
};

MneeLightPoint mnee_light_point(GpuLight l, vec2 u) {
#if !defined(GLINT_NO_SPHERES)
  if (l.shape.x == 0) {
    vec4 s = sphere_at(l.shape.y).center_radius;
    float z = 1.0 - 2.0 * u.x;
    float r = sqrt(max(0.0, (1.0 - z) * (1.0 + z)));
    vec3 normal = vec3(r * cos(TWO_PI * u.y), r * sin(TWO_PI * u.y), z);
    return MneeLightPoint(s.xyz + s.w * normal, normal, 4.0 * PI * s.w * s.w, l.shape.y);
  }
#endif
  GpuQuad q = quad_at(l.shape.y);
  vec3 y = q.p0.xyz + u.x * (q.p1.xyz - q.p0.xyz) + u.y * (q.p2.xyz - q.p0.xyz);
  return MneeLightPoint(y, q.normal.xyz, l.select.z, u_sphere_count + l.shape.y);
}

#if defined(GLINT_NO_COVERAGE) && defined(GLINT_NO_TRANSPARENT)
// 1 when the first surface from `origin` along the unit direction `dir` is primitive `ref` (-1:
// none, the ray escapes), else 0: every surface blocks light in such a scene.
vec3 mnee_transmittance(vec3 origin, vec3 dir, int ref, out SceneHit target) {
  target = intersect_scene(Ray(origin, dir));
  return target.ref == ref ? vec3(1.0) : vec3(0.0);
}

// The same without the hit record (only which primitive is hit matters).
vec3 mnee_transmittance(vec3 origin, vec3 dir, int ref) {
  return closest_primitive(Ray(origin, dir)).ref == ref ? vec3(1.0) : vec3(0.0);
}
#else
// What passes from primitive `ref` (-1: the environment) to `origin` along the unit direction
// `dir` through cut-outs and smooth thin glass (their straight transmittance, as shadow_ray
// takes it; the path tracer's chain state passes them too), 0 when another surface blocks it.
vec3 mnee_transmittance(vec3 origin, vec3 dir, int ref, out SceneHit target) {
  Ray ray = Ray(origin, dir);
  vec3 transmittance = vec3(1.0);
  for (int passes = 0; passes <= MAX_PASS_THROUGH; ++passes) {
    target = intersect_scene(ray);
    if (target.ref == ref) return transmittance;
    if (target.material < 0) break;
    GpuMaterial gm = material_at(target.material);
    vec4 color_tex = texture_lookup(gm.layers.x, target.uv);
    float coverage = gm.params.z * color_tex.a;
    vec3 n = dot(target.normal, dir) <= 0.0 ? target.normal : -target.normal;
    transmittance *= straight_transmittance(gm, color_tex, target.uv, coverage, dot(n, -dir));
    if (max_component(transmittance) <= 0.0) break;
    ray.origin = offset_surface_point(target.position, -n, target.error_scale);
  }
  return vec3(0.0);
}

vec3 mnee_transmittance(vec3 origin, vec3 dir, int ref) {
  SceneHit target;
  return mnee_transmittance(origin, dir, ref, target);
}
#endif

// The emitted radiance (times the light's coverage) reaching p1 from y, 0 when blocked or y is
// on the far side of a sphere light.
vec3 mnee_emission(MneeLightPoint lp, GpuLight l, vec3 p1, vec3 n1, float error_scale) {
  vec3 origin = offset_surface_point(p1, n1, error_scale);
  vec3 dir = normalize(lp.y - origin);
  if (l.shape.x == 0) {
    vec4 s = sphere_at(l.shape.y).center_radius;
    bool inside = dot(p1 - s.xyz, p1 - s.xyz) < s.w * s.w;
    if ((dot(lp.normal, p1 - lp.y) > 0.0) == inside) return vec3(0.0);
  }
  SceneHit hit;
  vec3 transmittance = mnee_transmittance(origin, dir, lp.ref, hit);
  if (max_component(transmittance) <= 0.0) return vec3(0.0);
  GpuMaterial gm = material_at(hit.material);
  float coverage = 1.0;
#if !defined(GLINT_NO_COVERAGE)
  coverage = gm.params.z * texture_lookup(gm.layers.x, hit.uv).a;
#endif
  return transmittance * coverage * material_emission(gm, hit.uv);
}

// The environment's radiance reaching p1 from direction omega, 0 when a surface blocks it.
vec3 mnee_environment_light(vec3 omega, vec3 p1, vec3 n1, float error_scale) {
  return mnee_transmittance(offset_surface_point(p1, n1, error_scale), omega, -1) * environment(omega);
}

// The chain's throughput, as the path tracer weights it (lib/bsdf.glsl): a mirror's Schlick
// Fresnel of its colour, thin glass's reflection Schlick's F of its index, glass's reflection
// F (weight 1, chosen with probability F), or glass's (1 - F) at both interfaces times its
// colour at each (the 1 / eta^2 of entering and the eta^2 of leaving cancel).
vec3 mnee_throughput(SurfaceMaterial caster, bool refracts, vec3 dir0, vec3 n1, vec3 d_in, vec3 n2) {
  float cos1 = -dot(dir0, n1);
  if (caster.type == MATERIAL_REFLECTIVE) return fresnel_schlick(caster.color, cos1);
  if (caster.type == MATERIAL_TRANSPARENT) return vec3(fresnel_schlick(dielectric_f0(caster.ior), cos1));
  if (!refracts) return vec3(fresnel_dielectric(cos1, caster.ior));
  float t = (1.0 - fresnel_dielectric(cos1, caster.ior)) * (1.0 - fresnel_dielectric(dot(d_in, n2), 1.0 / caster.ior));
  return t * caster.color * caster.color;
}

// What the caster and the sampled light point (or environment direction) give one MNEE
// sample at x.
struct MneeSetup {
  Meridian m;
  MneeLightPoint lp;
  GpuLight light;
  vec3 omega;  // parallel light: the direction towards the environment it comes from
  int caster;  // sphere index
  SurfaceMaterial caster_material;
  bool glass;  // the chain refracts through the ball (else it reflects off it)
  float scale;  // 1 / (pdf of y or omega, of the light, of the caster, of the chain)
};

// One chain's contribution at x (t a root): f Le T cos_y dω_y/dA_x (parallel light:
// f Le T dA_perp/dA_x), times visibility of its segments, over the pdfs. f is the plain BSDF
// (eval_bsdf's value over |n.wi|).
vec3 mnee_root(MneeSetup s, float t, float h, SurfaceMaterial m, vec3 x, vec3 n, vec3 wo,
               float error_scale) {
  Chain2D c = mnee_chain(s.m, t, s.glass, s.caster_material.ior);
  vec3 p1 = s.m.y + c.p1.x * s.m.axis + c.p1.y * s.m.side;
  vec3 p_last = s.m.y + c.p_last.x * s.m.axis + c.p_last.y * s.m.side;
  vec3 wi = normalize(p_last - x);
  float cos_x = abs(dot(n, wi));
  vec3 f = eval_bsdf(m, n, wo, wi);
  if (max_component(f) <= 0.0 || !(cos_x > 0.0)) return vec3(0.0);
  vec4 sphere = sphere_at(s.caster).center_radius;
  float caster_scale = sphere_error_scale(sphere.xyz, sphere.w);
  vec3 n1 = normalize(p1 - sphere.xyz);
  vec3 n_last = normalize(p_last - sphere.xyz);
  // Visibility: x to the chain's last point, the chord inside glass, p1 to the light.
  vec3 origin = offset_surface_point(x, dot(wi, n) > 0.0 ? n : -n, error_scale);
  vec3 transmittance = mnee_transmittance(origin, normalize(p_last - origin), s.caster);
  if (max_component(transmittance) <= 0.0) return vec3(0.0);
  vec3 d_in = normalize(p_last - p1);
  if (s.glass) transmittance *= mnee_transmittance(offset_surface_point(p1, -n1, caster_scale), d_in, s.caster);
  if (max_component(transmittance) <= 0.0) return vec3(0.0);
  vec3 le = s.m.parallel ? mnee_environment_light(s.omega, p1, n1, caster_scale)
                         : mnee_emission(s.lp, s.light, p1, n1, caster_scale);
  le *= transmittance;
  if (max_component(le) <= 0.0) return vec3(0.0);
  vec3 dir0 = s.m.parallel ? s.m.axis : cos(t) * s.m.axis + sin(t) * s.m.side;
  float cos_y = s.m.parallel ? 1.0 : abs(dot(s.lp.normal, dir0));
  vec3 throughput = mnee_throughput(s.caster_material, s.glass, dir0, n1, d_in, n_last);
  float jacobian = mnee_jacobian(s.m, t, h, c, n, s.glass, s.caster_material.ior);
  return (f / cos_x) * le * throughput * (cos_y * jacobian * s.scale);
}

// The root of g in [a, b] (g(a) g(b) < 0, both valid) by the Illinois variant of regula falsi;
// -1e30 when the bracket holds no root (an invalid point, or a jump rather than a zero).
float mnee_refine(Meridian m, bool glass, float ior, float a, float ga, float b, float gb) {
  int kept = 0;  // which end stayed last time (1: a, 2: b), for Illinois' halving
  for (int i = 0; i < MNEE_REFINE_STEPS; ++i) {
    float c = (a * gb - b * ga) / (gb - ga);
    if (!(c > min(a, b) && c < max(a, b))) c = 0.5 * (a + b);
    Chain2D ch = mnee_chain(m, c, glass, ior);
    if (!ch.valid) return -1e30;
    float gc = mnee_residual(m, ch);
    if (gc == 0.0) return c;
    if ((gc < 0.0) == (ga < 0.0)) {
      a = c;
      ga = gc;
      if (kept == 2) gb *= 0.5;
      kept = 2;
    } else {
      b = c;
      gb = gc;
      if (kept == 1) ga *= 0.5;
      kept = 1;
    }
  }
  float root = abs(ga) < abs(gb) ? a : b;
  Chain2D ch = mnee_chain(m, root, glass, ior);
  float tolerance = 1e-4 * length(m.x2 - ch.p_last);
  return ch.valid && abs(mnee_residual(m, ch)) <= tolerance ? root : -1e30;
}

// Picks a light point (or an environment direction) and a caster (random numbers of
// mnee_dimension) and the plane of the chains from it to x; false when no chain of that choice
// can count (y or x inside the caster, x on the axis, a light MNEE does not sample, or more
// bounces than max_bounces allow).
bool mnee_setup(vec3 x, int bounce, out MneeSetup s) {
  uint dim = mnee_dimension(bounce);
  float u_light = sample_1d(dim);
  float u_caster = sample_1d(dim + 1u);
  vec2 u_point = sample_2d(dim);
  float pick = u_caster * float(u_caster_count);
  s.caster = u_casters[min(int(pick), u_caster_count - 1)];
  GpuSphere sphere = sphere_at(s.caster);
  vec3 c = sphere.center_radius.xyz;
  float r = sphere.center_radius.w;
  float env_select = mnee_environment_select();
  s.m.parallel = u_light < env_select;
  float light_pdf;  // of the point in area measure, or of the direction in solid angle
  if (s.m.parallel) {
#if !defined(GLINT_NO_ENV_TEXTURE)
    EnvironmentSample es = sample_environment(u_point, u_env_rotation);
    if (!es.valid || !(es.pdf > 0.0)) return false;
    s.omega = es.wi;
    light_pdf = env_select * es.pdf;
    s.lp.y = c + 2.0 * r * s.omega;  // on the axis, upstream of the sphere
#endif
  } else {
    s.light = light_at(pick_light((u_light - env_select) / (1.0 - env_select)));
    if (!mnee_light_supported(s.light)) return false;
    s.lp = mnee_light_point(s.light, u_point);
    light_pdf = (1.0 - env_select) * s.light.select.x / s.lp.area;
  }
  GpuMaterial gm = material_at(sphere.material.x);
  s.caster_material = surface_material(gm, vec4(1.0), vec2(0.0));
  // A glass ball's chain refracts or (with probability 1/2, the rest of u_caster) reflects.
  bool refractive = s.caster_material.type == MATERIAL_REFRACTIVE;
  s.glass = refractive && fract(pick) < 0.5;
  // The path tracer reaches the light at bounce + 2 (reflection) or + 3 (refraction), after
  // scattering at bounce + 1 (and + 2), which max_bounces must allow.
  if (bounce + (s.glass ? 2 : 1) >= u_max_bounces) return false;
  vec3 to_c = c - s.lp.y;
  s.m.dist = length(to_c);
  s.m.radius = r;
  if (!(s.m.dist > r) || dot(x - c, x - c) <= r * r) return false;
  s.m.y = s.lp.y;
  s.m.axis = to_c / s.m.dist;
  vec3 rel = x - s.lp.y;
  float along = dot(rel, s.m.axis);
  vec3 perp = rel - along * s.m.axis;
  float rho = length(perp);
  if (!(rho > 1e-6 * s.m.dist)) return false;  // x on the axis (a set of measure zero)
  s.m.side = perp / rho;
  s.m.x2 = vec2(along, rho);
  s.scale = float(u_caster_count) * (refractive ? 2.0 : 1.0) / light_pdf;
  return true;
}

// The refined root of a bracket (a, g(a), b, g(b)) and its chain's contribution; 0 for an
// empty bracket (a = b).
vec3 mnee_bracket(MneeSetup s, vec4 bracket, float h, SurfaceMaterial m, vec3 x, vec3 n, vec3 wo,
                  float error_scale) {
  if (!(bracket.z > bracket.x)) return vec3(0.0);
  float root = mnee_refine(s.m, s.glass, s.caster_material.ior, bracket.x, bracket.y, bracket.z, bracket.w);
  return root > -1e29 ? mnee_root(s, root, h, m, x, n, wo, error_scale) : vec3(0.0);
}

// MNEE at the non-delta vertex x (n on wo's side): the sum over every chain found of one light
// point and caster, throughput not included (as direct_light). The scan and the refinement are
// not nested: under SIMD execution a loop nested in the scan would run whenever any lane had a
// bracket at that grid point.
vec3 manifold_next_event(SurfaceMaterial m, vec3 x, vec3 n, vec3 wo, float error_scale, int bounce) {
  MneeSetup s;
  if (!mnee_setup(x, bounce, s)) return vec3(0.0);
  float ior = s.caster_material.ior;
  float t_max = (s.m.parallel ? s.m.radius : asin(min(1.0, s.m.radius / s.m.dist))) * (1.0 - 1e-4);
  // A reflection's chains with t < 0 stay on the far side of the axis from x (the reflected
  // ray's distance from the axis only grows): the scan covers (0, t_max) for reflections.
  float lo = s.glass ? -t_max : 0.0;
  float step = (t_max - lo) / float(MNEE_GRID - 1);
  vec2 rotation = vec2(cos(step), sin(step));  // the scan's directions by rotation, no trig
  // Up to three brackets (a, g(a), b, g(b)), in variables rather than an array: llvmpipe keeps
  // a dynamically indexed array in memory. At most three chains reach a point through a glass
  // ball, one off a mirror; a fourth sign change (noise at a fold) is dropped.
  vec4 bracket0 = vec4(0.0), bracket1 = vec4(0.0), bracket2 = vec4(0.0);
  int found = 0;
  vec2 dir = mnee_ray_direction(s.m, lo);
  Chain2D ca = mnee_chain_along(s.m, mnee_ray_origin(s.m, lo), dir, s.glass, ior);
  float ga = mnee_residual(s.m, ca);
  for (int i = 1; i < MNEE_GRID; ++i) {
    float t = lo + float(i) * step;
    if (!s.m.parallel)
      dir = vec2(dir.x * rotation.x - dir.y * rotation.y, dir.x * rotation.y + dir.y * rotation.x);
    Chain2D cb = mnee_chain_along(s.m, mnee_ray_origin(s.m, t), dir, s.glass, ior);
    float gb = mnee_residual(s.m, cb);
    if (ca.valid && cb.valid && (ga < 0.0) != (gb < 0.0)) {
      vec4 bracket = vec4(t - step, ga, t, gb);
      if (found == 0) bracket0 = bracket;
      else if (found == 1) bracket1 = bracket;
      else if (found == 2) bracket2 = bracket;
      ++found;
    }
    ga = gb;
    ca = cb;
  }
  float h = 5e-3 * step;  // of the central difference in mnee_jacobian
  vec3 sum = mnee_bracket(s, bracket0, h, m, x, n, wo, error_scale);
  if (found > 1) sum += mnee_bracket(s, bracket1, h, m, x, n, wo, error_scale);
  if (found > 2) sum += mnee_bracket(s, bracket2, h, m, x, n, wo, error_scale);
  return sum;
}
