// `glint render`: parse the command line, load the project, run a render session to its
// target with the device's policy (renderer/render_policy.h), write the image. Prints a
// progress line and a short summary; --verbose adds the details of the device and the program.
#include "app/render_command.h"

#include <unistd.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "app/command_line.h"
#include "app/convergence_log.h"
#include "app/progress_bar.h"
#include "app/render_size.h"
#include "renderer/atomic_file.h"
#include "renderer/backend_choice.h"
#include "renderer/gl_context.h"
#include "renderer/gpu_renderer.h"
#include "renderer/image.h"
#include "renderer/image_metrics.h"
#include "renderer/project_file.h"
#include "renderer/render_metadata.h"
#include "renderer/render_output.h"
#include "renderer/render_part.h"
#include "renderer/render_policy.h"
#include "renderer/render_session.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

const char* const kUsage =
    "usage: glint render PROJECT.glint -o OUT.{png,hdr,exr} [--spp N | --time SECONDS |\n"
    "                    --samples A:B] [--target-error E] [--adaptive]\n"
    "                    [--width W] [--height H] [--seed S] [--generic-shader]\n"
    "                    [--mnee | --no-mnee]\n"
    "                    [--reference REF.exr --log OUT.csv]\n"
    "                    [--sampler pcg|sobol] [--no-light-sampling] [--no-env-sampling]\n"
    "                    [--no-roulette] [--clamp L] [--accel auto|loop|bvh]\n"
    "                    [--restart auto|at-once|together]\n"
    "                    [--backend auto|fragment|compute] [--work-group WxH]\n"
    "                    [--denoise [--denoise-quality fast|high]] [--aovs] [--alpha] [--verbose]\n"
    "\n"
    "Renders a project headlessly (EGL; no window or display needed). Prints a progress line\n"
    "while it renders, then what it wrote (size, spp, time, samples per second), why it stopped\n"
    "(--target-error) and the warnings and notes that matter (biased options, discarded\n"
    "samples, the backend cache).\n"
    "  --verbose          also print the details: the OpenGL device, the trace backend and\n"
    "                     its timing, the closest-hit structure, adaptive sampling's start,\n"
    "                     the program the last pass traced with\n"
    "  -o, --output FILE  .png is tonemapped with the project's exposure and tonemap;\n"
    "                     .hdr and .exr hold the linear radiance (EXR: float32 RGBA)\n"
    "  --spp N            samples per pixel (default 64)\n"
    "  --time SECONDS     render for this long instead of a fixed sample count\n"
    "  --samples A:B      a part of a render: exactly its samples A to B-1 (those a render\n"
    "                     of B samples takes), to an .exr whose header names the render;\n"
    "                     `glint merge` joins parts covering 0:N into the N-sample render\n"
    "  --target-error E   render until the estimated relMSE of the image is at most E\n"
    "                     (estimated from each pixel's sample variance, no reference\n"
    "                     needed; never before 16 spp); --spp and --time are then caps,\n"
    "                     both may be given, whichever comes first ends it (default cap:\n"
    "                     --spp 4096). A line on stderr names the limit that ended it\n"
    "  --adaptive         adaptive sampling: from 16 spp on, a pixel whose estimated error\n"
    "                     per sample is below the image's mean skips passes (but takes every\n"
    "                     8th), so samples go where the noise is; --spp is then the most any\n"
    "                     pixel takes. Off by default: without it every pixel gets the same\n"
    "                     samples and a render is reproduced bit for bit\n"
    "  --width W          image width (default: the project's film; with only one of\n"
    "  --height H         width or height given, the other keeps the film's aspect)\n"
    "  --seed S           sample sequence (default: the project's render.seed)\n"
    "  --generic-shader   trace with the program that has every feature compiled in, not\n"
    "                     the one specialised to the scene (same image; for measuring)\n"
    "  --mnee, --no-mnee  manifold next-event estimation of caustics through smooth spheres in\n"
    "                     every scene that has them, or in none (default: where a lamp is small\n"
    "                     against the ball, or a sky with a sun lights matte surfaces); the\n"
    "                     same image in expectation, for measuring\n"
    "  --reference REF    linear .exr or .hdr image of the same size to measure the error\n"
    "                     against (give it with --log)\n"
    "  --log OUT.csv      convergence log against --reference: one row at 1, 2, 4, 8, ...\n"
    "                     samples per pixel and at the final --spp if that is not a power of\n"
    "                     two (with --time: powers of two only). Columns:\n"
    "                     spp,seconds,gpu_seconds,relmse,estimated_relmse,relmse_trimmed,\n"
    "                     mape,mean_bias,nonfinite\n"
    "                     seconds: time spent rendering so far; the clock (and --time) is\n"
    "                       paused while a checkpoint reads the image back and computes errors\n"
    "                     gpu_seconds: sum of GL timer queries around the trace passes\n"
    "                     relmse: mean of (x-r)^2/(r^2+0.01) over pixels and channels;\n"
    "                       relmse_trimmed drops the worst 0.1% of pixels first\n"
    "                     estimated_relmse: the same error estimated without the reference,\n"
    "                       from the pixels' sample variance (as --target-error uses it)\n"
    "                     mape: mean of |x-r|/(|r|+0.01); mean_bias: relative error of the\n"
    "                       mean luminance; nonfinite: non-finite samples discarded\n"
    "Denoising and auxiliary images (Intel Open Image Denoise, loaded at run time):\n"
    "  --denoise          the output is denoised with the albedo and normal images: BIASED\n"
    "                     (less noise, but blur and artefacts that no sample count removes);\n"
    "                     an .exr keeps the noisy colour as the layer noisy.R/G/B. Refused\n"
    "                     with --reference/--log, whose error is the unbiased render's. Where\n"
    "                     the library is missing, says so and writes the noisy image;\n"
    "                     the noisy image is written before denoising, so a denoiser that\n"
    "                     fails leaves it in place (exit 1)\n"
    "  --denoise-quality Q  high (the default) or fast (quicker, less detail)\n"
    "  --aovs             .exr only: also write the albedo (albedo.R/G/B) and the normal\n"
    "                     (N.X/Y/Z, world space) at the first surface that is not a perfect\n"
    "                     mirror or smooth glass, averaged over the samples like the colour\n"
    "  --alpha            a transparent background for compositing (.png or .exr): alpha\n"
    "                     is the fraction of each pixel's camera rays that hit a surface\n"
    "                     (0 where the environment shows, fractional on edges); the\n"
    "                     environment still lights the scene. EXR: premultiplied RGBA;\n"
    "                     PNG: straight alpha\n"
    "Estimator (not saved in projects; the defaults are unbiased):\n"
    "  --sampler S        random numbers: sobol (the default: Owen-scrambled Sobol points,\n"
    "                     low discrepancy, less noise per sample; each seed is its own\n"
    "                     scramble, so renders with different seeds are independent) or pcg\n"
    "                     (independent hashed streams, for comparison)\n"
    "  --no-light-sampling  follow BSDF samples only: no shadow rays to emitting shapes\n"
    "  --no-env-sampling  no shadow rays to the environment map\n"
    "  --no-roulette      no Russian roulette (every path runs to max_bounces)\n"
    "  --clamp L          scale samples brighter than luminance L down to L: removes\n"
    "                     fireflies but BIASED (darker); never use it for references\n"
    "Closest hits (same image either way; for measuring):\n"
    "  --accel A          auto (the default: a BVH from 48 shapes, and wherever the loop\n"
    "                     would exceed Mesa llvmpipe's shader loop limit), loop (test every\n"
    "                     shape for every ray), or bvh (bounding volume hierarchy, built\n"
    "                     before the clock starts; --verbose prints its build time)\n"
    "Path regeneration (same image either way; for measuring):\n"
    "  --restart R        when a pixel whose path has ended starts its next sample: auto\n"
    "                     (the default: together with its SIMD group where the environment\n"
    "                     gives light, at once where it is black), at-once, or together\n"
    "Trace backend (same image either way):\n"
    "  --backend B        auto (the default: the faster on this device, timed once on a\n"
    "                     small scene and cached in $XDG_CACHE_HOME/glint/backend.json,\n"
    "                     else ~/.cache/glint/backend.json, per GL vendor, renderer and\n"
    "                     version), fragment (a fragment shader per pass) or compute (a\n"
    "                     compute shader writing the accumulation in place)\n"
    "  --work-group WxH   the compute shader's work group (default 8x8; for measuring)\n"
    "Exit codes: 0 done, 1 bad project or failed render (or the output or log could not\n"
    "be written), 2 bad arguments (also: a --width/--height beyond the film limits, a\n"
    "--log or -o that would overwrite the project, the reference or each other).\n";

// The sample cap of --target-error when neither --spp nor --time is given.
constexpr int64_t kTargetErrorDefaultCap = 4096;
// Without a terminal (a log file), the progress line is printed at most this often.
constexpr double kLoggedProgressSeconds = 5.0;

struct Options {
  std::string project;
  std::string output;
  std::optional<long> spp;
  std::optional<double> seconds;
  std::optional<SampleRange> samples;  // --samples A:B: a render part
  std::optional<double> target_error;
  std::optional<long> width, height, seed;
  std::string reference;  // with `log`: write a convergence log against this image
  std::string log;
  RenderOptions estimator;
  bool generic_shader = false;
  MneeChoice mnee = MneeChoice::automatic;
  std::optional<TraceBackend> backend;  // nullopt: the automatic choice
  WorkGroup work_group;
  RenderOutputOptions output_options;  // --denoise, --denoise-quality, --aovs
  bool denoise_quality_given = false;
  bool verbose = false;
};

// ---- Parsing: a table of the options, then the checks of the options together.

double parse_positive(const std::string& option, const std::string& text, const char* what) {
  char* end = nullptr;
  double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v) || v <= 0)
    throw UsageError{option + " expects a positive " + what + ", got '" + text + "'"};
  return v;
}

// A luminance the GPU holds as a normal float: a smaller one would be flushed to zero (which
// turns the clamp off), a larger one becomes infinity.
float parse_clamp(const std::string& option, const std::string& text) {
  const double v = parse_positive(option, text, "luminance");
  if (v < std::numeric_limits<float>::min() || v > std::numeric_limits<float>::max()) {
    char range[96];
    std::snprintf(range, sizeof range, "from %.3g to %.3g (what a GPU's float holds)",
                  double(std::numeric_limits<float>::min()), double(std::numeric_limits<float>::max()));
    throw UsageError{option + " expects a luminance " + range + ", got '" + text + "'"};
  }
  return static_cast<float>(v);
}

// One of the named values of an option: "--sampler expects pcg or sobol, got 'x'" otherwise.
template <class T>
T parse_choice(const std::string& option, const std::string& text,
               std::initializer_list<std::pair<const char*, T>> choices) {
  std::string names;
  size_t i = 0;
  for (const auto& [name, value] : choices) {
    if (text == name) return value;
    names += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + std::string(name);
    ++i;
  }
  throw UsageError{option + " expects " + names + ", got '" + text + "'"};
}

using Flag = void (*)(Options&);
const std::pair<const char*, Flag> kFlags[] = {
    {"--adaptive", [](Options& o) { o.estimator.adaptive = true; }},
    {"--no-light-sampling", [](Options& o) { o.estimator.light_sampling = false; }},
    {"--no-env-sampling", [](Options& o) { o.estimator.environment_sampling = false; }},
    {"--no-roulette", [](Options& o) { o.estimator.russian_roulette = false; }},
    {"--generic-shader", [](Options& o) { o.generic_shader = true; }},
    {"--mnee", [](Options& o) { o.mnee = MneeChoice::always; }},
    {"--no-mnee", [](Options& o) { o.mnee = MneeChoice::never; }},
    {"--denoise", [](Options& o) { o.output_options.denoise = true; }},
    {"--aovs", [](Options& o) { o.output_options.aovs = true; }},
    {"--alpha", [](Options& o) {
       o.output_options.alpha = true;
       o.estimator.transparent_background = true;
     }},
    {"--verbose", [](Options& o) { o.verbose = true; }},
};

// An option with a value: (options, the option as typed, its value).
using Text = const std::string&;
using Setter = void (*)(Options&, Text, Text);
const std::pair<const char*, Setter> kValueOptions[] = {
    {"-o", [](Options& o, Text, Text v) { o.output = v; }},
    {"--output", [](Options& o, Text, Text v) { o.output = v; }},
    {"--spp", [](Options& o, Text a, Text v) { o.spp = parse_integer_option(a, v, 1, 1L << 30); }},
    {"--time", [](Options& o, Text a, Text v) { o.seconds = parse_positive(a, v, "number of seconds"); }},
    {"--samples",
     [](Options& o, Text, Text v) {
       o.samples = parse_sample_range(v);
       if (!o.samples) throw UsageError{"--samples expects A:B with 0 <= A < B <= 4294967296, got '" + v + "'"};
     }},
    {"--target-error", [](Options& o, Text a, Text v) { o.target_error = parse_positive(a, v, "relMSE"); }},
    {"--width", [](Options& o, Text a, Text v) { o.width = parse_integer_option(a, v, 1, 16384); }},
    {"--height", [](Options& o, Text a, Text v) { o.height = parse_integer_option(a, v, 1, 16384); }},
    {"--seed", [](Options& o, Text a, Text v) { o.seed = parse_integer_option(a, v, 0, 4294967295L); }},
    {"--reference", [](Options& o, Text, Text v) { o.reference = v; }},
    {"--log", [](Options& o, Text, Text v) { o.log = v; }},
    {"--backend",
     [](Options& o, Text a, Text v) {
       o.backend = parse_choice<std::optional<TraceBackend>>(
           a, v, {{"auto", std::nullopt}, {"fragment", TraceBackend::fragment}, {"compute", TraceBackend::compute}});
     }},
    {"--work-group",
     [](Options& o, Text, Text v) {
       const auto g = parse_work_group(v);
       if (!g) throw UsageError{"--work-group expects WxH with W*H from 1 to 1024 (e.g. 8x8), got '" + v + "'"};
       o.work_group = *g;
     }},
    {"--sampler",
     [](Options& o, Text a, Text v) {
       o.estimator.sampler =
           parse_choice<SamplerKind>(a, v, {{"pcg", SamplerKind::pcg}, {"sobol", SamplerKind::sobol}});
     }},
    {"--accel",
     [](Options& o, Text a, Text v) {
       o.estimator.accel =
           parse_choice<Accel>(a, v, {{"auto", Accel::automatic}, {"loop", Accel::loop}, {"bvh", Accel::bvh}});
     }},
    {"--restart",
     [](Options& o, Text a, Text v) {
       o.estimator.restart = parse_choice<PathRestart>(
           a, v,
           {{"auto", PathRestart::automatic}, {"at-once", PathRestart::at_once}, {"together", PathRestart::together}});
     }},
    {"--clamp", [](Options& o, Text a, Text v) { o.estimator.clamp = parse_clamp(a, v); }},
    {"--denoise-quality",
     [](Options& o, Text a, Text v) {
       o.output_options.quality =
           parse_choice<DenoiseQuality>(a, v, {{"fast", DenoiseQuality::fast}, {"high", DenoiseQuality::high}});
       o.denoise_quality_given = true;
     }},
};

// Reads argv[i] (and its value, advancing i) into `o`.
void parse_argument(Options& o, int argc, char** argv, int& i) {
  if (parse_table_option(o, kFlags, kValueOptions, argc, argv, i)) return;
  const std::string a = argv[i];
  if (!o.project.empty()) throw UsageError{"unexpected argument '" + a + "' (one project at a time)"};
  o.project = a;
}

// How many samples: --spp, --time, --target-error and --samples together.
void check_sample_options(Options& o) {
  if (o.samples && (o.spp || o.seconds || o.target_error || o.estimator.adaptive))
    throw UsageError{"--samples renders an exact range: it takes no --spp, --time, --target-error or --adaptive"};
  if (o.samples && o.output_options.alpha)
    throw UsageError{"--samples writes a render part: --alpha is not for parts"};
  if (o.samples && (o.output_options.denoise || o.output_options.aovs))
    throw UsageError{"--samples writes a render part: denoise the merged image (--denoise and --aovs are not "
                     "for parts)"};
  if (o.spp && o.seconds && !o.target_error)
    throw UsageError{"give --spp or --time, not both (both are caps only with --target-error)"};
  if (o.samples) {
    o.spp = o.samples->count();
    o.estimator.first_sample = static_cast<uint32_t>(o.samples->first);
    if (fs::path(o.output).extension() != ".exr")
      throw UsageError{"--samples writes a render part: the output '" + o.output + "' must be an .exr"};
  }
}

// What is written: the image's format, the log and the denoised layers.
void check_output_options(const Options& o) {
  if (!o.log.empty() && o.reference.empty())
    throw UsageError{"--log needs --reference REF.exr (the image the error is measured against)"};
  if (!o.reference.empty() && o.log.empty())
    throw UsageError{"--reference needs --log OUT.csv (where the convergence log is written)"};
  if (const auto problem = output_format_problem(o.output)) throw UsageError{"output '" + o.output + "' " + *problem};
  if (o.output_options.denoise && !o.log.empty())
    throw UsageError{"--denoise is biased and is never used with --reference/--log (the log "
                     "measures the unbiased render's true error): leave one out"};
  if (o.denoise_quality_given && !o.output_options.denoise) throw UsageError{"--denoise-quality needs --denoise"};
  if (o.output_options.alpha && fs::path(o.output).extension() == ".hdr")
    throw UsageError{"--alpha needs a .png or .exr output (.hdr has no alpha), not '" + o.output + "'"};
  if (o.output_options.aovs && fs::path(o.output).extension() != ".exr")
    throw UsageError{"--aovs needs an .exr output (the images are written as its layers), not '" + o.output + "'"};
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 0; i < argc; ++i) parse_argument(o, argc, argv, i);
  if (o.project.empty()) throw UsageError{"no project file given"};
  if (o.output.empty()) throw UsageError{"no output file given (-o OUT.png|.hdr|.exr)"};
  check_sample_options(o);
  check_output_options(o);
  return o;
}

// ---- Files: what the command writes is never what it reads.

// A path with its symbolic links resolved as far as they exist (and the last one even when
// its target does not), for comparing files that may not exist yet.
fs::path resolved(const fs::path& path) {
  fs::path p = path;
  try {
    p = write_target(path);
  } catch (const FileWriteError&) {  // a loop: compare the path as given
  }
  std::error_code ec;
  const fs::path absolute = fs::absolute(p, ec);
  if (ec) return p.lexically_normal();
  const fs::path canonical = fs::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal() : canonical;
}

// Whether two paths name the same file: the same inode where both exist (hard links, bind
// mounts), else the same resolved path.
bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) {
    const bool same = fs::equivalent(a, b, ec);
    if (!ec) return same;
  }
  return resolved(a) == resolved(b);
}

// Files the command writes must not be the files it reads, nor each other: --log would
// otherwise truncate the project or the reference before the render, and -o overwrite the
// reference after it.
void check_distinct_files(const Options& o) {
  struct Named {
    const char* what;
    const std::string& path;
  };
  const Named inputs[] = {{"the project", o.project}, {"the reference", o.reference}};
  const Named outputs[] = {{"--log", o.log}, {"-o", o.output}};
  for (const Named& out : outputs) {
    if (out.path.empty()) continue;
    for (const Named& in : inputs)
      if (!in.path.empty() && same_file(out.path, in.path))
        throw UsageError{std::string(out.what) + " " + out.path + " is " + in.what + " (" + in.path +
                         "): it would be overwritten"};
  }
  if (!o.log.empty() && same_file(o.log, o.output))
    throw UsageError{"--log " + o.log + " is the output image (-o " + o.output + ")"};
}

// ---- Messages: a summary for everyone, details with --verbose.

[[gnu::format(printf, 2, 3)]] void print_detail(bool verbose, const char* format, ...) {
  if (!verbose) return;
  va_list args;
  va_start(args, format);
  std::vfprintf(stderr, format, args);
  va_end(args);
}

void print_backend(const Options& o, const HeadlessGLContext& context, const RenderPolicy& policy) {
  if (policy.device_choice && !policy.device_choice->note.empty())
    std::fprintf(stderr, "note: %s\n", policy.device_choice->note.c_str());
  print_detail(o.verbose, "glint: OpenGL %s on %s (%s)\n", gl_version_string().c_str(), gl_renderer_name().c_str(),
               context.platform().c_str());
  if (!policy.device_choice) {
    print_detail(o.verbose, "glint: trace backend: %s (--backend)\n", backend_name(policy.backend));
    return;
  }
  const BackendChoice& c = *policy.device_choice;
  const std::string why = policy.backend_reason.empty() ? "" : "; " + policy.backend_reason;
  print_detail(o.verbose,
               "glint: trace backend: %s (auto, %s: fragment %.0f spp/s, compute %.0f spp/s on the timing scene; "
               "%.2f s%s)\n",
               backend_name(policy.backend), c.from_cache ? "cached" : "timed now", c.fragment_spp_s, c.compute_spp_s,
               c.seconds, why.c_str());
}

// The options' notes (biased estimators) and the program's details, before the render.
void print_render_setup(const Options& o, const Scene& scene, const GpuRenderer& renderer) {
  if (o.estimator.clamp > 0)
    std::fprintf(stderr, "note: --clamp %g is biased (fireflies are scaled down)\n", o.estimator.clamp);
  if (renderer.uses_bvh()) {
    const GpuRenderer::BvhStats& b = renderer.bvh_stats();
    print_detail(o.verbose,
                 "glint: closest hits by BVH: %zu nodes, depth %d, built in %.2f ms, at most %d nodes per ray\n",
                 b.nodes, b.depth, b.seconds * 1e3, b.max_steps);
  } else {
    print_detail(o.verbose, "glint: closest hits by the loop over %zu shapes\n",
                 scene.spheres.size() + scene.quads.size());
  }
  if (renderer.exceeds_llvmpipe_loop_limit() && on_llvmpipe())
    std::fprintf(stderr,
                 "warning: one sample of %s may run more loop iterations than Mesa's llvmpipe "
                 "allows a shader (65535; too many bounces, or too many shapes for the loop with "
                 "--accel loop): parts of this image may be wrong (use a GPU)\n",
                 o.project.c_str());
  if (o.estimator.adaptive)
    print_detail(o.verbose, "glint: adaptive sampling from %d spp (every %dth pass samples every pixel)\n",
                 o.estimator.adaptive_min_samples, o.estimator.adaptive_every);
}

// The progress line after a step: redrawn in place on a terminal, else a line every
// kLoggedProgressSeconds.
class ProgressLine {
 public:
  explicit ProgressLine(const Options& o) : options_(o), interactive_(isatty(STDERR_FILENO)) {}

  void show(const RenderSession& s, GpuRenderer& renderer) {
    const double elapsed = s.seconds();
    if (!interactive_ && elapsed - last_shown_ < kLoggedProgressSeconds) return;
    const int64_t target = s.options().target.samples;
    std::string line = options_.seconds ? format_time_progress(elapsed, *options_.seconds, s.samples())
                                        : format_progress(s.traced_samples(), target, elapsed, "spp");
    // The estimated error beside the bar: the session's own when it targets one, else a fresh
    // one (a small read-back; every kLoggedProgressSeconds when not on a terminal).
    double estimated = s.estimated_relmse();  // -1: not known (fewer than two samples)
    if (!options_.target_error && s.samples() > 0) {
      const ErrorEstimate e = renderer.estimate_error();
      estimated = e.known() ? e.relmse : -1;
    }
    line += format_error_estimate(estimated, options_.target_error.value_or(0));
    std::fprintf(stderr, interactive_ ? "\r%s\033[K" : "%s\n", line.c_str());
    last_shown_ = elapsed;
  }
  void end() const {
    if (interactive_) std::fputc('\n', stderr);
  }

 private:
  const Options& options_;
  const bool interactive_;
  double last_shown_ = -1e9;
};

// After the render: why it stopped (an error target) and the program it traced with.
void print_render_end(const Options& o, const RenderSession& session, const GpuRenderer& renderer) {
  if (o.target_error)
    std::fprintf(stderr, "glint: stopped by the %s: estimated relMSE %.4g (target %g) at %lld spp, %.2f s\n",
                 stop_reason_text(session.stop_reason()), session.estimated_relmse(), *o.target_error,
                 static_cast<long long>(session.samples()), session.seconds());
  std::string defines = renderer.last_pass_defines();
  for (char& c : defines) c = c == '\n' ? ' ' : c;
  print_detail(o.verbose, "glint: last pass traced with the %s program%s%s\n",
               renderer.last_pass_generic() ? "generic" : "specialised", defines.empty() ? "" : ": ", defines.c_str());
}

// ---- The render.

RenderTarget render_target(const Options& o) {
  if (!o.target_error) return o.seconds ? RenderTarget{0, *o.seconds} : RenderTarget{o.spp ? *o.spp : 64, 0};
  RenderTarget target;
  target.error = *o.target_error;
  target.seconds = o.seconds.value_or(0);
  target.samples = o.spp ? *o.spp : o.seconds ? 0 : kTargetErrorDefaultCap;
  return target;
}

// A renderer synced to the scene with its program built (the BVH too), before the clock starts.
std::unique_ptr<GpuRenderer> prepare_renderer(const Options& o, const Scene& scene, TraceBackend backend, int width,
                                              int height) {
  GpuRendererOptions options;
  options.force_generic_shader = o.generic_shader;
  options.mnee = o.mnee;
  options.work_group = o.work_group;
  options.backend = backend;
  auto renderer = std::make_unique<GpuRenderer>(options);
  renderer->set_options(o.estimator);
  // Before the render, so that a missing library is known before a long wait.
  if (o.output_options.denoise && denoising_available_or_warn_once("glint render"))
    std::fprintf(stderr, "note: --denoise is biased (the denoiser trades noise for blur)\n");
  renderer->set_aovs_enabled(o.output_options.denoise || o.output_options.aovs);
  try {
    renderer->sync(scene, width, height);
  } catch (const ImageError& e) {  // the driver cannot hold the textures: name the project too
    throw std::runtime_error(o.project + ": " + e.what());
  }
  renderer->prepare_specialised_program();
  return renderer;
}

// Writes the image (or the render part) and prints what was written; returns the exit code
// (1 when the denoiser failed: the noisy image is written).
int write_outputs(const Options& o, const Scene& scene, GpuRenderer& renderer, double seconds) {
  const int width = renderer.width(), height = renderer.height();
  std::string denoise_failure;
  if (o.samples) {
    save_render_part(renderer, part_info(scene, o.estimator, width, height, *o.samples), o.output);
  } else {
    RenderOutputOptions output_options = o.output_options;
    output_options.metadata = render_metadata(scene, o.estimator, renderer.sample_count());
    const RenderOutputReport written = save_render_output(renderer, scene.display, o.output, output_options);
    if (written.denoised)
      std::fprintf(stderr, "glint: denoised (biased) with Open Image Denoise on the %s in %.2f s\n",
                   written.device.c_str(), written.denoise_seconds);
    if (written.denoise_failed) denoise_failure = written.note;
  }
  if (double discarded = nonfinite_count(renderer.read_accumulation()); discarded > 0)
    std::fprintf(stderr, "warning: %.0f samples were discarded (non-finite, or a BVH traversal past its step cap)\n",
                 discarded);
  const int64_t spp = renderer.sample_count();
  const double pixel_samples = double(spp) * width * height;
  std::fprintf(stderr, "glint: wrote %s (%dx%d, %lld spp, %.2f s, %.1f spp/s, %.2f Msamples/s)\n", o.output.c_str(),
               width, height, static_cast<long long>(spp), seconds, spp / seconds, pixel_samples / seconds * 1e-6);
  if (denoise_failure.empty()) return 0;
  std::fprintf(stderr, "glint render: %s\n", denoise_failure.c_str());
  return 1;
}

int render(const Options& o) {
  check_distinct_files(o);
  // Fail before rendering, not after, when the image could not be written: a missing or
  // read-only folder, a name too long for the file system.
  if (const auto problem = file_write_problem(o.output)) throw std::runtime_error(o.output + ": " + *problem);
  Scene scene = load_project(o.project);
  const auto [width, height] = render_size(o.width, o.height, scene.film);
  if (o.seed) scene.render.seed = static_cast<uint32_t>(*o.seed);
  std::unique_ptr<ConvergenceLog> log;
  if (!o.log.empty()) log = std::make_unique<ConvergenceLog>(o.log, load_reference(o.reference, width, height));

  auto context = HeadlessGLContext::create();
  const RenderPolicy policy =
      batch_render_policy({width, height, render_target(o), o.estimator.adaptive, log != nullptr, o.backend});
  print_backend(o, *context, policy);
  const std::unique_ptr<GpuRenderer> renderer = prepare_renderer(o, scene, policy.backend, width, height);
  print_render_setup(o, scene, *renderer);

  RenderSession session(*renderer, policy.session.options);
  ProgressLine progress(o);
  session.run(policy.session.step_seconds, [&](RenderSession& s) {
    if (log) log->after_step(s, *renderer);
    progress.show(s, *renderer);
  });
  progress.end();
  print_render_end(o, session, *renderer);

  const int code = write_outputs(o, scene, *renderer, session.seconds());
  if (log) std::fprintf(stderr, "glint: %s\n", log->close().c_str());
  return code;
}

}  // namespace

int run_render_command(int argc, char** argv) {
  Options o;
  if (int code = parse_command_line("glint render", kUsage, argc, argv, parse, o); code >= 0) return code;
  try {
    return render(o);
  } catch (const UsageError& e) {  // arguments that conflict with each other or the project
    std::fprintf(stderr, "glint render: %s\n", e.message.c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint render: %s\n", e.what());
    return 1;
  }
}

}  // namespace glint
