// The draws of a trace pass (docs/DESIGN.md §3.1): binding a trace program with the renderer's
// tables, textures and film, drawing a band of image rows with all of a pass's draws, the
// warm-up draw that makes a driver compile before the clock starts, and the program worker's
// job that draws the same way in its own context.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "renderer/trace_backend.h"

namespace glint {

class AovPass;
class FilmBuffers;
class GlProgram;
class SceneTables;
class SceneTextures;
struct ProgramJob;
struct TraceUniforms;

// What a trace draw binds besides the program, all owned by the renderer.
struct TraceBindings {
  const TraceUniforms& uniforms;
  const SceneTables& tables;
  const SceneTextures& textures;
  const FilmBuffers& film;
  GLuint vao;
  TraceBackend backend;
  WorkGroup work_group;
};

// Which pixels a pass samples: adaptive sampling's uniforms (RenderOptions::adaptive) and the
// region (GpuRenderer::set_sample_region).
struct AdaptiveUniforms {
  bool enabled = false;
  float threshold = 0;  // the image's mean error per sample at the last estimate
  int min_samples = 16;
  int every = 8;
  bool region_on = false;
  glm::ivec4 region{0};  // x0, y0, x1, y1: pixels [x0, x1) x [y0, y1), image rows top first
  // Pixels' sample counts may differ (a region was used since the reset): each continues from
  // its own.
  bool per_pixel_counts = false;
};

// One draw: adds `samples` samples to pixels that have `samples_before`, at adaptive sampling's
// pass `pass_index`, from film side `source` into the other one (fragment) or in place (compute).
struct TraceDraw {
  int samples = 0;
  int64_t samples_before = 0;
  int64_t pass_index = 0;
  int source = 0;
};

// Binds `p` with the uniforms, tables, textures and targets of `draw`; returns p.
GlProgram& bind_trace_draw(GlProgram& p, const TraceBindings& b, const AdaptiveUniforms& adaptive,
                           const TraceDraw& draw);

// A band of a pass: `samples` per pixel over rows [first, last), in draws of at most
// `samples_per_draw`, each followed by the AOV pass's when `aovs`.
struct TraceBand {
  int samples = 0;
  int samples_per_draw = 1;
  int first = 0;
  int last = 0;
};
struct BandResult {
  int side = 0;   // the film side that holds the band's result
  int draws = 0;  // every band of a pass takes the same number
};
// Each draw of the band in turn: a pixel depends on its own previous state only, so a band may
// take all of the pass's draws before the next band starts. The fragment path alternates sides
// from draw to draw; every band takes the same number of draws, so all end on the same side.
// `start` holds the samples before the pass, its pass index and its first side.
BandResult trace_band(GlProgram& p, const TraceBindings& b, const AdaptiveUniforms& adaptive,
                      const TraceDraw& start, const TraceBand& band, AovPass* aovs);

// One pixel of the spare side, no samples (it is overwritten by the next pass): a driver that
// compiles at the first draw (Mesa's llvmpipe JITs then, 0.6-1 s) does it here, not inside the
// first timed pass. The compute path has no spare side: one group with a resolution of 0x0,
// whose invocations all return before touching the images. Waits for the GPU.
void warm_up_trace_draw(GlProgram& p, const TraceBindings& b, const AdaptiveUniforms& adaptive,
                        const TraceDraw& draw);

// A job for the program worker (renderer/program_worker.h): link the trace program with
// `defines`, then draw one pixel with it in the state a trace pass draws in (four RGBA32F
// targets; the renderer's textures on units 0-6 and tables on theirs, whose formats and sampling
// enter the compiled code's key), so that the driver compiles there the code the renderer's
// first pass will look up. The names are captured now; should the renderer replace a texture
// meanwhile, the driver compiles again at that first pass (only slower). Not submitted.
std::shared_ptr<ProgramJob> trace_variant_job(const std::string& defines, const TraceBindings& b);

}  // namespace glint
