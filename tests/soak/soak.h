// A soak test of the renderer: the editor's ViewportRenderer frame after frame (sync, trace,
// update_display; an occasional read-back) for a long run on one headless context, measuring
// what a session of hours could accumulate: resident memory and GL objects (a leak per frame or
// per edit) and the accumulated mean (float32 drift over 10^5 passes).
//
// The run has three phases on the viewport's GpuRenderer:
//   1. edits: a drag-like edit every frame (sphere position, material colour, roughness and
//      type, environment intensity, camera orbit, in turn) and an exposure change every M
//      frames; memory is read after warm-up and at the end of the phase (each reading the least
//      over 8 further frames without edits);
//   2. accumulation: the unedited scene for `frames` frames of `spp` samples, exposure changes
//      every M frames (which must not restart it), display read-backs; the accumulated mean
//      is read at checkpoints and memory at the end;
//   3. reference: an independent estimate of the same expectation, `reference_batches`
//      accumulations of `reference_spp` samples with their own seeds, summed in double.
// The accumulated mean must agree with the reference within k_sigma standard errors (from the
// batches' spread), for the whole image and each quadrant, at every checkpoint and over the
// samples after the 32-bit wrap of the sample-stream index (see choose_soak_seed).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "tests/soak/resource_probe.h"

namespace glint::soak {

struct SoakConfig {
  std::filesystem::path project;
  int width = 8, height = 8;
  int64_t frames = 100000;     // accumulation frames (phase 2)
  int spp = 1;                 // samples per pixel per frame
  int checkpoints = 4;         // mean readings in phase 2, evenly spaced (plus one at the wrap)
  int64_t warmup_frames = 1000;  // phase-1 frames before the first memory reading
  int64_t edit_frames = 10000;   // phase-1 frames after warm-up (one edit each)
  int exposure_every = 7;      // M: an exposure change every M frames (both phases)
  int readback_every = 1000;   // the display image is read back every this many frames
  int reference_batches = 1000;
  int reference_spp = 100;
  double k_sigma = 4;          // tolerance of every comparison, in standard errors
  int paired_spp = 0;          // > 0: also trace the soak's own samples again in passes of this
                               // many samples, and compare (float rounding only, no noise)
  // Called after every frame of phases 1 and 2 with the frame's number in its phase (tests use
  // it to plant a leak and see the checks fail).
  std::function<void(int64_t frame)> after_frame;
};

struct MemoryReading {
  std::string when;
  int64_t frame = 0;
  Resident rss;  // KiB
  int64_t heap_bytes = 0;
  int64_t heap_held = 0;  // heap_held_bytes at the end of the reading
  GlObjectCounts gl;
};

// Mean luminance of the whole image and its four quadrants.
constexpr int kRegions = 5;
const char* region_name(int region);

struct Comparison {
  std::string what;
  int64_t samples = 0;  // per pixel in the soak's estimate
  double soak[kRegions] = {}, reference[kRegions] = {}, se[kRegions] = {}, z[kRegions] = {};
  double worst_abs_z() const;
};

struct SoakReport {
  uint32_t seed = 0;
  int64_t wrap_sample = -1;  // first sample index whose stream index has wrapped past 2^32
  std::vector<MemoryReading> memory;
  std::vector<Comparison> comparisons;  // checkpoints, the part after the wrap, the end
  int64_t edits = 0, edit_resets = 0;   // edits made, and those that restarted accumulation
  int64_t exposure_changes = 0, exposure_resets = 0;  // the latter must be 0
  int64_t readbacks = 0;
  int64_t final_samples = 0;
  double relative_se_whole = 0;  // of the soak's final whole-image mean
  // paired_spp > 0: the same samples accumulated in passes of paired_spp.
  // Soak minus paired, relative to paired, per region; the worst pixel (relative to its value,
  // or to 1e-3 of the image mean if darker).
  double paired_relative[kRegions] = {}, paired_worst_pixel_relative = 0;
  double seconds_edits = 0, seconds_accumulation = 0, seconds_reference = 0;
  std::string gl_renderer;
};

// pcg_hash(seed) offsets every sample index of a PCG stream (rng_seed in shaders/lib/rng.glsl
// hashes sample_index + pcg_hash(seed) in 32 bits). The first seed from `from` whose offset
// makes that sum wrap at sample `wrap_at` (+- 10%, a multiple of `spp`); returns it and sets
// *wrap_sample.
uint32_t choose_soak_seed(uint32_t from, int64_t wrap_at, int spp, int64_t* wrap_sample);

// True when the sample streams (seed a, samples [0, na)) and (seed b, [0, nb)) share an index.
bool streams_overlap(uint32_t seed_a, int64_t na, uint32_t seed_b, int64_t nb);

// Runs the three phases; needs a current OpenGL 4.5 context. Progress lines go to `log` if set.
SoakReport run_soak(const SoakConfig& config, std::FILE* log = nullptr);

// Bound on the growth of heap_in_use_bytes from the reading after warm-up to the end: a leak of
// one byte per frame over the 10^5-frame run, or of 7 bytes per edit over 10^4 edits, exceeds
// it; the soak's own buffers are allocated before the first reading.
constexpr int64_t kHeapGrowthBound = 64 * 1024;

// Growth of anonymous RSS from the reading after warm-up to the end, less the growth of what
// malloc holds (KiB): memory outside malloc (driver mappings, JIT code).
int64_t unexplained_rss_growth_kib(const SoakReport& report);
// Its bound: 4 MiB or 2% of the first reading, whichever is larger (see soak.cpp for why).
int64_t rss_growth_bound_kib(const SoakReport& report);

std::string format_report(const SoakConfig& config, const SoakReport& report);

// The finest precision bench/reports/RESULTS.md states for a bias (the standard error of the
// white-furnace and huge-sphere rows, 0.01%): accumulation drift must stay below it.
constexpr double kStatedPrecision = 1e-4;

// Every check the run fails, in words; empty when it passed. The checks: every edit restarted
// the accumulation and no exposure change did; the GL object counts after warm-up and at the
// end are equal; the heap in use grew by at most kHeapGrowthBound and anonymous RSS outside
// malloc by at most rss_growth_bound_kib; every comparison is within k_sigma
// standard errors in every region; with paired_spp, the difference from the paired run is below
// kStatedPrecision in every region and every pixel.
std::vector<std::string> failures(const SoakConfig& config, const SoakReport& report);

}  // namespace glint::soak
