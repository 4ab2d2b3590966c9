// How the renderer estimates an image, as opposed to what the scene is: these are not saved in
// projects. The defaults are unbiased. The default sampler is Owen-scrambled Sobol (less error
// per sample, bench/reports/RESULTS.md); every seed is an independent scramble, so error bars from seed
// spreads hold as they do for PCG's independent numbers (tests/unit/shader_sobol_test.cpp,
// tests/gl/light_sampling_test.cpp). The switches exist so that the bench can measure each
// technique and users can trade bias for noise.
#pragma once

#include <cstdint>

namespace glint {

enum class SamplerKind { pcg, sobol };

// How closest hits are found: chosen from the scene (renderer/bvh.h, use_bvh), or forced (for
// measuring; the image is the same either way).
enum class Accel { automatic, loop, bvh };

// When path regeneration starts a lane's next sample (renderer/path_restart.h): chosen from the
// scene, or forced (for measuring; the image is the same either way).
enum class PathRestart { automatic, at_once, together };

struct RenderOptions {
  bool light_sampling = true;        // next-event estimation + MIS for emitting spheres and quads
  bool environment_sampling = true;  // ... and for an environment map (importance-sampled)
  bool russian_roulette = true;      // unbiased path termination after a few bounces
  SamplerKind sampler = SamplerKind::sobol;
  float clamp = 0;                   // firefly clamp: largest sample luminance; 0 = off. BIASED.
  Accel accel = Accel::automatic;
  PathRestart restart = PathRestart::automatic;
  // Where in the render's sample sequence this render starts: a render of n samples takes
  // samples first_sample .. first_sample+n-1, the very samples a render of first_sample+n
  // samples takes there (for every sampler). A sample range A:B (`glint render --samples`)
  // is first_sample = A and B-A samples; merging ranges 0..N gives the N-sample render.
  uint32_t first_sample = 0;
  // Adaptive sampling (docs/DESIGN.md §4.2): pixels whose estimated error per sample is below the
  // image's mean wait, except every adaptive_every-th pass, once they hold adaptive_min_samples.
  // Off by default: a uniform render's every pixel gets the same samples, so sample ranges of
  // a render add up to it exactly and tests compare images bit for bit.
  bool adaptive = false;
  int adaptive_min_samples = 16;
  int adaptive_every = 8;
  // A transparent background for compositing (`glint render --alpha`, the export's checkbox):
  // camera rays that find the environment add nothing, so the image is premultiplied by its
  // alpha, the primary rays' coverage (GpuRenderer::read_coverage); the environment still
  // lights the scene.
  bool transparent_background = false;
  bool operator==(const RenderOptions&) const = default;
};

}  // namespace glint
