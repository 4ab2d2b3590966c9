// Which spheres manifold next-event estimation sends light through (shaders/lib/
// manifold_nee.glsl, docs/DESIGN.md §3.10), and whether a scene needs it compiled in.
#pragma once

#include <vector>

#include "renderer/scene.h"

namespace glint {

// The shader's MNEE_MAX_CASTERS: casters beyond the first this many are left to path tracing.
inline constexpr int kMaxMneeCasters = 8;

// A smooth mirror or smooth refractive material as the path tracer sees it (shaders/lib/bsdf.glsl,
// is_delta_material), untextured, opaque and not emitting: light through it follows one chain
// per sphere, which the shader solves exactly.
bool is_mnee_caster_material(const Material& m);

// Indices of the spheres of caster material and positive radius, the first kMaxMneeCasters.
std::vector<int> mnee_casters(const Scene& scene);

// True when MNEE can add light: a caster, an emitter it samples (a sphere or a parallelogram
// quad) and a surface that is not delta (where next-event estimation runs).
bool scene_needs_mnee(const Scene& scene);

// A lamp MNEE samples is small against a caster when its area is at most this share of the
// caster's cross-section (pi r^2). Below it path tracing rarely finds the lamp through the
// ball and MNEE pays for its cost; above it, it did not at equal time (docs/DESIGN.md §3.10:
// lamp/cross-section 0.02 gained, 0.43 and 0.53 lost; the threshold lies between, not tuned).
inline constexpr double kMneeSmallLampShare = 0.1;

// True when the scene needs MNEE and has a lamp small against a caster (kMneeSmallLampShare):
// the renderer's automatic choice (GpuRendererOptions::mnee).
bool mnee_pays_off(const Scene& scene);

}  // namespace glint
