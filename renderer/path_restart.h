// When a lane of the trace shader's path regeneration starts its next sample
// (shaders/lib/sample_accumulation.glsl, add_samples): at once, or together with its SIMD group once no
// lane of the group has a path in flight. Both give the same image (each sample is the same,
// added in the same order); only the speed differs, and which is faster depends on the scene.
//
// Measured on llvmpipe (Mesa 25, bench/reports/THROUGHPUT.md, "Restarting paths together"): starting
// together traced 0.98-1.22x the samples per second of starting at once on 11 scenes under a
// lit environment (faster on 9: paths escape after a few bounces, so their lengths are alike,
// and starting at once runs the start-up code whenever any lane of the group has ended, next
// to rays of other depths), and 0.88-0.96x on 5 closed rooms under a black environment (paths
// end by roulette or the bounce limit, their lengths differ widely, and waiting lanes idle).
// Without group votes in the driver (GL_ARB_shader_group_vote) every lane starts at once.
#pragma once

#include "renderer/render_options.h"
#include "renderer/scene.h"

namespace glint {

// Whether the environment gives any light: a texture with a positive intensity, or a colour
// with a positive component times a positive intensity.
bool environment_emits(const Environment& env);

// The policy for a scene: automatic is together where the environment emits and at once where
// it is black; the other two are forced (for measuring).
bool restart_paths_together(PathRestart restart, const Environment& env);

}  // namespace glint
