// Which spheres manifold next-event estimation sends light through (shaders/lib/
// manifold_nee.glsl, docs/DESIGN.md §3.10), and whether a scene needs it compiled in.
#pragma once

#include <vector>

#include "renderer/scene.h"

namespace glint {

// The shader's MNEE_MAX_CASTERS: casters beyond the first this many are left to path tracing.
inline constexpr int kMaxMneeCasters = 8;

// A smooth mirror, refractive or thin-glass material as the path tracer sees it (shaders/lib/
// bsdf.glsl, is_delta_material), untextured, opaque and not emitting: light through it (off it,
// for thin glass, whose transmission next-event estimation already follows) takes one chain per
// sphere, which the shader solves exactly.
bool is_mnee_caster_material(const Material& m);

// Indices of the spheres of caster material and positive radius, the first kMaxMneeCasters.
std::vector<int> mnee_casters(const Scene& scene);

// True when MNEE can add light: a caster, a light it samples (an emitting sphere or
// parallelogram quad, or an environment map) and a surface that is not delta (where
// next-event estimation runs).
bool scene_needs_mnee(const Scene& scene);

// A lamp MNEE samples is small against a caster when its area is at most this share of the
// caster's cross-section (pi r^2). Below it path tracing rarely finds the lamp through the
// ball and MNEE pays for its cost; above it, it did not at equal time (docs/DESIGN.md §3.10:
// lamp/cross-section 0.02 gained, 0.43 and 0.53 lost; the threshold lies between, not tuned).
inline constexpr double kMneeSmallLampShare = 0.1;

// True when the scene needs MNEE and has a lamp small against a caster (kMneeSmallLampShare).
bool mnee_pays_off(const Scene& scene);

// An environment map is peaked, like a sky with a sun, when its brightest texels that cover
// kPeakSolidAngleShare of the sphere hold at least this share of its power (environment_peak_share):
// path tracing then finds the sun through a ball as rarely as a small lamp (projects/assets/
// sky.hdr: 0.25); a smooth sky (about kPeakSolidAngleShare) is left to it. Not tuned: between
// those two.
inline constexpr double kPeakSolidAngleShare = 0.001;
inline constexpr double kMneePeakedEnvironmentShare = 0.1;

// Which lights MNEE samples (the shader's u_mnee_lights), a bit set.
inline constexpr int kMneeLamps = 1;
inline constexpr int kMneeEnvironment = 2;

// The renderer's choice (GpuRendererOptions::mnee): none when the scene does not need MNEE;
// else its lamps where mnee_pays_off, and its environment map where that is peaked
// (environment_peak_share, 0 without a map) and every surface that is neither a lamp nor smooth
// is matte; or every light MNEE can sample when `always`. With glossy surfaces the sun's own
// highlights and glossy caustics, which MNEE does not sample, ruled the error, and MNEE's cost
// (about 2.3x a sample) lost at equal time: docs/DESIGN.md §3.10 (bench/scenes/env_dof.glint,
// matte but for a mirror ball, gained 3x; roughness_ladder, showcase and projects/default lost
// 1.2-1.7x).
int mnee_lights(const Scene& scene, double environment_peak_share, bool always);

}  // namespace glint
