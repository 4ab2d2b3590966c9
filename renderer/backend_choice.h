// Which entry point of the path tracer to use on this device (docs/DESIGN.md §3.3): the faster
// of the fragment and the compute shader, timed once on a small fixed scene and remembered per
// device. Why both exist: on Mesa's llvmpipe the fragment shader is faster; NVIDIA's datacenter
// GPUs run fragment shaders on only a few of their units and compute shaders on all of them.
//
// The cache is a small JSON file, $XDG_CACHE_HOME/glint/backend.json (else
// ~/.cache/glint/backend.json), keyed by GL_VENDOR, GL_RENDERER and GL_VERSION together with a
// digest of the trace shaders' text and of the timing's method (a driver update, a changed path
// tracer or a changed timing times again). A
// cache that cannot be read or written never stops a render: the choice is timed instead, and
// `note` says so in one line. The cache is untrusted (renderer/state_file.h): a FIFO, a folder,
// a huge file or a mistyped field is treated as no cache, and it is never written through a
// symbolic link.
#pragma once

#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>

#include "renderer/trace_backend.h"

namespace glint {

struct BackendChoice {
  TraceBackend backend = TraceBackend::fragment;
  bool from_cache = false;    // read from the cache, nothing timed
  double fragment_spp_s = 0;  // of the timing scene (from the cache when from_cache)
  double compute_spp_s = 0;
  double seconds = 0;         // wall clock spent choosing (compiles and timing included)
  std::string note;           // one line when the cache could not be read or written, else ""
};

// GL_VENDOR | GL_RENDERER | GL_VERSION of the current context.
std::string device_key();

// The cache file from the environment ($XDG_CACHE_HOME where it is an absolute path, else
// $HOME/.cache); nullopt when neither is set (then nothing is cached).
std::optional<std::filesystem::path> default_backend_cache_file();

// Both backends' samples per pixel per second on the timing scene (8 matte balls on a floor
// sphere under a constant sky, 4 bounces, 128x128), each compiled and warmed up first, then
// timed in alternation (5 passes of 32 samples each) and the median taken.
// Needs a current GL 4.5 context.
struct BackendTiming {
  double fragment_spp_s = 0;
  double compute_spp_s = 0;
};
BackendTiming time_backends();

// Compute is chosen only when it is this much faster: on llvmpipe the two are within the
// timing's noise of each other on some scenes (bench/reports/THROUGHPUT.md), and a choice that flips
// with the machine's load would be cached either way; where compute matters (GPUs that run
// fragment shaders on a few units) it is expected to be many times faster.
constexpr double kComputeMargin = 1.1;
bool prefers_compute(const BackendTiming& timing);

// The side of the square tiles in which Mesa's llvmpipe rasterises and shades, one tile per
// thread at a time (its TILE_SIZE).
inline constexpr int kLlvmpipeTileSize = 64;
// The tiles, whole or part, across `pixels` pixels (at least one).
inline int llvmpipe_tiles_across(int pixels) { return std::max(1, (pixels + kLlvmpipeTileSize - 1) / kLlvmpipeTileSize); }

// On Mesa's llvmpipe the fragment shader is shaded one 64x64 tile per thread at a time, so an
// image of fewer tiles than threads leaves threads idle, where the compute shader's work groups
// spread over all of them (a 64x64 Cornell box on 2 CPUs: 2.1x with compute). True when an
// image of width x height has fewer such tiles than `threads`.
bool fewer_llvmpipe_tiles_than_threads(int width, int height, int threads);

// The cached choice for the current context's device, or time_backends() and the cache
// written (renderer/atomic_file.h). An unreadable or corrupt cache is timed again and
// replaced; other devices' entries are kept.
BackendChoice choose_backend(const std::optional<std::filesystem::path>& cache_file =
                                 default_backend_cache_file());

}  // namespace glint
