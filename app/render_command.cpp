#include "app/render_command.h"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include "app/command_line.h"
#include "app/progress_bar.h"
#include "app/render_size.h"
#include "renderer/atomic_file.h"
#include "renderer/backend_choice.h"
#include "renderer/gl_context.h"
#include "renderer/gpu_renderer.h"
#include "renderer/image.h"
#include "renderer/image_metrics.h"
#include "renderer/project_file.h"
#include "renderer/render_part.h"
#include "renderer/render_output.h"
#include "renderer/render_session.h"
#include "renderer/scene_validation.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

const char* const kUsage =
    "usage: glint render PROJECT.glint -o OUT.{png,hdr,exr} [--spp N | --time SECONDS |\n"
    "                    --samples A:B] [--target-error E] [--adaptive]\n"
    "                    [--width W] [--height H] [--seed S] [--generic-shader]\n"
    "                    [--reference REF.exr --log OUT.csv]\n"
    "                    [--sampler pcg|sobol] [--no-light-sampling] [--no-env-sampling]\n"
    "                    [--no-roulette] [--clamp L] [--accel auto|loop|bvh]\n"
    "                    [--restart auto|at-once|together]\n"
    "                    [--backend auto|fragment|compute] [--work-group WxH]\n"
    "                    [--denoise [--denoise-quality fast|high]] [--aovs]\n"
    "\n"
    "Renders a project headlessly (EGL; no window or display needed).\n"
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
    "                     --spp 4096). The last line on stderr names the limit that ended it\n"
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
    "                     before the clock starts; its build time is printed)\n"
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
// The pixel samples of a render's first pass, whose time sizes the passes after it; the
// time a pass grows to (traced in bands, or untiled on an image of one band), and the time of
// one band of its rows (without --time).
constexpr int64_t kFirstPassPixelSamples = 1 << 17;
constexpr double kPassSeconds = 4.0;
constexpr double kUntiledPassSeconds = 1.0;
constexpr double kBandSeconds = 0.25;

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
  std::optional<TraceBackend> backend;  // nullopt: the automatic choice
  WorkGroup work_group;
  RenderOutputOptions output_options;  // --denoise, --denoise-quality, --aovs
  bool denoise_quality_given = false;
};

long parse_integer(const std::string& option, const std::string& text, long lo, long hi) {
  char* end = nullptr;
  errno = 0;
  long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0 || v < lo || v > hi)
    throw UsageError{option + " expects an integer from " + std::to_string(lo) + " to " +
                     std::to_string(hi) + ", got '" + text + "'"};
  return v;
}

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

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 0; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError{a + " needs a value"};
      return argv[++i];
    };
    if (a == "-o" || a == "--output") o.output = value();
    else if (a == "--spp") o.spp = parse_integer(a, value(), 1, 1L << 30);
    else if (a == "--time") o.seconds = parse_positive(a, value(), "number of seconds");
    else if (a == "--samples") {
      std::string v = value();
      o.samples = parse_sample_range(v);
      if (!o.samples) throw UsageError{"--samples expects A:B with 0 <= A < B <= 4294967296, got '" + v + "'"};
    }
    else if (a == "--target-error") o.target_error = parse_positive(a, value(), "relMSE");
    else if (a == "--adaptive") o.estimator.adaptive = true;
    else if (a == "--width") o.width = parse_integer(a, value(), 1, 16384);
    else if (a == "--height") o.height = parse_integer(a, value(), 1, 16384);
    else if (a == "--seed") o.seed = parse_integer(a, value(), 0, 4294967295L);
    else if (a == "--reference") o.reference = value();
    else if (a == "--log") o.log = value();
    else if (a == "--backend") {
      std::string v = value();
      if (v == "auto") o.backend.reset();
      else if (auto b = parse_backend(v)) o.backend = *b;
      else throw UsageError{"--backend expects auto, fragment or compute, got '" + v + "'"};
    } else if (a == "--work-group") {
      std::string v = value();
      if (auto g = parse_work_group(v)) o.work_group = *g;
      else throw UsageError{"--work-group expects WxH with W*H from 1 to 1024 (e.g. 8x8), got '" + v + "'"};
    } else if (a == "--sampler") {
      std::string v = value();
      if (v == "pcg") o.estimator.sampler = SamplerKind::pcg;
      else if (v == "sobol") o.estimator.sampler = SamplerKind::sobol;
      else throw UsageError{"--sampler expects pcg or sobol, got '" + v + "'"};
    } else if (a == "--accel") {
      std::string v = value();
      if (v == "auto") o.estimator.accel = Accel::automatic;
      else if (v == "loop") o.estimator.accel = Accel::loop;
      else if (v == "bvh") o.estimator.accel = Accel::bvh;
      else throw UsageError{"--accel expects auto, loop or bvh, got '" + v + "'"};
    } else if (a == "--restart") {
      std::string v = value();
      if (v == "auto") o.estimator.restart = PathRestart::automatic;
      else if (v == "at-once") o.estimator.restart = PathRestart::at_once;
      else if (v == "together") o.estimator.restart = PathRestart::together;
      else throw UsageError{"--restart expects auto, at-once or together, got '" + v + "'"};
    } else if (a == "--no-light-sampling") o.estimator.light_sampling = false;
    else if (a == "--no-env-sampling") o.estimator.environment_sampling = false;
    else if (a == "--no-roulette") o.estimator.russian_roulette = false;
    else if (a == "--clamp") o.estimator.clamp = parse_clamp(a, value());
    else if (a == "--generic-shader") o.generic_shader = true;
    else if (a == "--denoise") o.output_options.denoise = true;
    else if (a == "--aovs") o.output_options.aovs = true;
    else if (a == "--denoise-quality") {
      std::string v = value();
      if (v == "fast") o.output_options.quality = DenoiseQuality::fast;
      else if (v == "high") o.output_options.quality = DenoiseQuality::high;
      else throw UsageError{"--denoise-quality expects fast or high, got '" + v + "'"};
      o.denoise_quality_given = true;
    }
    else if (!a.empty() && a[0] == '-') throw UsageError{"unknown option " + a};
    else if (o.project.empty()) o.project = a;
    else throw UsageError{"unexpected argument '" + a + "' (one project at a time)"};
  }
  if (o.project.empty()) throw UsageError{"no project file given"};
  if (o.output.empty()) throw UsageError{"no output file given (-o OUT.png|.hdr|.exr)"};
  if (o.samples && (o.spp || o.seconds || o.target_error || o.estimator.adaptive))
    throw UsageError{"--samples renders an exact range: it takes no --spp, --time, --target-error or --adaptive"};
  if (o.samples && (o.output_options.denoise || o.output_options.aovs))
    throw UsageError{"--samples writes a render part: denoise the merged image (--denoise and --aovs are not for parts)"};
  if (o.spp && o.seconds && !o.target_error)
    throw UsageError{"give --spp or --time, not both (both are caps only with --target-error)"};
  if (o.samples) {
    o.spp = o.samples->count();
    o.estimator.first_sample = static_cast<uint32_t>(o.samples->first);
    if (std::filesystem::path(o.output).extension() != ".exr")
      throw UsageError{"--samples writes a render part: the output '" + o.output + "' must be an .exr"};
  }
  if (!o.log.empty() && o.reference.empty())
    throw UsageError{"--log needs --reference REF.exr (the image the error is measured against)"};
  if (!o.reference.empty() && o.log.empty())
    throw UsageError{"--reference needs --log OUT.csv (where the convergence log is written)"};
  auto ext = std::filesystem::path(o.output).extension().string();
  if (ext != ".png" && ext != ".hdr" && ext != ".exr")
    throw UsageError{"output '" + o.output + "' must end in .png, .hdr or .exr"};
  if (o.output_options.denoise && !o.log.empty())
    throw UsageError{"--denoise is biased and is never used with --reference/--log (the log "
                     "measures the unbiased render's true error): leave one out"};
  if (o.denoise_quality_given && !o.output_options.denoise)
    throw UsageError{"--denoise-quality needs --denoise"};
  if (o.output_options.aovs && ext != ".exr")
    throw UsageError{"--aovs needs an .exr output (the images are written as its layers), not '" +
                     o.output + "'"};
  return o;
}

// The reference of --reference: a linear image of exactly the render's size.
Image load_reference(const std::string& path, int width, int height) {
  ImageInfo info = probe_image(path);  // throws ImageError naming the file
  if (!info.high_dynamic_range)
    throw std::runtime_error(path + ": a reference must be linear radiance (.exr or .hdr), "
                             "not an 8-bit display image");
  if (info.width != width || info.height != height)
    throw std::runtime_error(path + ": the reference is " + std::to_string(info.width) + "x" +
                             std::to_string(info.height) + " but the render is " +
                             std::to_string(width) + "x" + std::to_string(height));
  return load_image(path, ColorEncoding::linear);
}

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

// The convergence log, with every write checked: a full disk or /dev/full fails the command
// with the OS reason instead of losing rows silently.
class LogFile {
 public:
  explicit LogFile(std::string path) : path_(std::move(path)), file_(std::fopen(path_.c_str(), "w")) {
    if (!file_) fail();
  }
  ~LogFile() {
    if (file_) std::fclose(file_);
  }
  LogFile(const LogFile&) = delete;
  LogFile& operator=(const LogFile&) = delete;

  // Writes and flushes one line (so a long render can be watched, and an interrupted one
  // keeps its rows).
  void write_line(const std::string& line) {
    if (std::fputs(line.c_str(), file_) == EOF || std::fputc('\n', file_) == EOF ||
        std::fflush(file_) != 0)
      fail();
  }
  void close() {
    std::FILE* file = file_;
    file_ = nullptr;
    if (std::fclose(file) != 0) fail();
  }

 private:
  [[noreturn]] void fail() const {
    throw std::runtime_error(path_ + ": cannot write the log: " + std::strerror(errno));
  }
  std::string path_;
  std::FILE* file_;
};

}  // namespace

int run_render_command(int argc, char** argv) {
  Options o;
  if (int code = parse_command_line("glint render", kUsage, argc, argv, parse, o); code >= 0) return code;

  try {
    check_distinct_files(o);
    // Fail before rendering, not after, when the image could not be written: a missing or
    // read-only folder, a name too long for the file system.
    if (const auto problem = file_write_problem(o.output))
      throw std::runtime_error(o.output + ": " + *problem);
    Scene scene = load_project(o.project);
    const auto [width, height] = render_size(o.width, o.height, scene.film);
    if (o.seed) scene.render.seed = static_cast<uint32_t>(*o.seed);

    std::optional<Image> reference;
    std::optional<LogFile> log;
    if (!o.log.empty()) {
      reference = load_reference(o.reference, width, height);
      log.emplace(o.log);
      log->write_line("spp,seconds,gpu_seconds,relmse,estimated_relmse,relmse_trimmed,mape,mean_bias,nonfinite");
    }

    auto context = HeadlessGLContext::create();
    std::fprintf(stderr, "glint: OpenGL %s on %s (%s)\n", gl_version_string().c_str(),
                 gl_renderer_name().c_str(), context->platform().c_str());
    // llvmpipe runs a thread per CPU (the back-end switch and the bands below count on it).
    const int cpu_threads = static_cast<int>(std::thread::hardware_concurrency());
    GpuRendererOptions renderer_options;
    renderer_options.force_generic_shader = o.generic_shader;
    renderer_options.work_group = o.work_group;
    if (o.backend) {
      renderer_options.backend = *o.backend;
      std::fprintf(stderr, "glint: trace backend: %s (--backend)\n", backend_name(*o.backend));
    } else {
      const BackendChoice choice = choose_backend();
      renderer_options.backend = choice.backend;
      if (!choice.note.empty()) std::fprintf(stderr, "note: %s\n", choice.note.c_str());
      // The device's choice is timed at 128x128; an image too small for llvmpipe's fragment
      // path to use every thread takes the compute shader (the same image).
      std::string why;
      if (choice.backend == TraceBackend::fragment && on_llvmpipe() &&
          fewer_llvmpipe_tiles_than_threads(width, height, cpu_threads)) {
        renderer_options.backend = TraceBackend::compute;
        why = "; compute for an image of fewer 64x64 llvmpipe tiles than its " + std::to_string(cpu_threads) + " threads";
      }
      std::fprintf(stderr, "glint: trace backend: %s (auto, %s: fragment %.0f spp/s, compute %.0f spp/s on the timing scene; %.2f s%s)\n",
                   backend_name(renderer_options.backend), choice.from_cache ? "cached" : "timed now",
                   choice.fragment_spp_s, choice.compute_spp_s, choice.seconds, why.c_str());
    }
    GpuRenderer renderer(renderer_options);
    renderer.set_options(o.estimator);
    // Before the render, so that a missing library is known before a long wait.
    if (o.output_options.denoise && denoising_available_or_warn_once("glint render"))
      std::fprintf(stderr, "note: --denoise is biased (the denoiser trades noise for blur)\n");
    renderer.set_aovs_enabled(o.output_options.denoise || o.output_options.aovs);
    if (o.estimator.clamp > 0)
      std::fprintf(stderr, "note: --clamp %g is biased (fireflies are scaled down)\n", o.estimator.clamp);
    try {
      renderer.sync(scene, width, height);
    } catch (const ImageError& e) {  // the driver cannot hold the textures: name the project too
      throw std::runtime_error(o.project + ": " + e.what());
    }
    renderer.prepare_specialised_program();
    if (renderer.uses_bvh()) {
      const GpuRenderer::BvhStats& b = renderer.bvh_stats();
      std::fprintf(stderr, "glint: closest hits by BVH: %zu nodes, depth %d, built in %.2f ms, at most %d nodes per ray\n",
                   b.nodes, b.depth, b.seconds * 1e3, b.max_steps);
    } else {
      std::fprintf(stderr, "glint: closest hits by the loop over %zu shapes\n", scene.spheres.size() + scene.quads.size());
    }
    if (renderer.exceeds_llvmpipe_loop_limit() && on_llvmpipe())
      std::fprintf(stderr,
                   "warning: one sample of %s may run more loop iterations than Mesa's llvmpipe "
                   "allows a shader (65535; too many bounces, or too many shapes for the loop with "
                   "--accel loop): parts of this image may be wrong (use a GPU)\n",
                   o.project.c_str());

    RenderSessionOptions session_options;
    if (o.target_error) {
      session_options.target.error = *o.target_error;
      session_options.target.seconds = o.seconds.value_or(0);
      session_options.target.samples = o.spp ? *o.spp : o.seconds ? 0 : kTargetErrorDefaultCap;
    } else {
      session_options.target = o.seconds ? RenderTarget{0, *o.seconds} : RenderTarget{o.spp ? *o.spp : 64, 0};
    }
    if (o.estimator.adaptive)
      std::fprintf(stderr, "glint: adaptive sampling from %d spp (every %dth pass samples every pixel)\n",
                   o.estimator.adaptive_min_samples, o.estimator.adaptive_every);
    session_options.checkpoints = log.has_value();
    // Passes of many samples, traced in bands of rows: a pass's draws trace up to the loop
    // budget's samples per pixel, and in a draw of few samples the lanes whose paths end early
    // wait for the longest path of their SIMD group (path regeneration refills them only with
    // the pixel's further samples). So: a first pass of about kFirstPassPixelSamples samples in
    // all (tens of milliseconds on llvmpipe), then passes grown by rate to about
    // kPassSeconds, each traced in bands of about kBandSeconds so that the progress bar moves.
    // Not with --time, whose target is checked between passes only, nor with --adaptive, whose
    // threshold is refreshed between passes (GpuRenderer::begin_pass): there passes start at
    // one sample and double while under a quarter of a second, untiled.
    const bool long_passes = !o.seconds && !o.estimator.adaptive;
    if (long_passes) {
      // Bands only where the image holds more than one (else untiled, and shorter passes so
      // that the bar still moves).
      session_options.band_rows = band_rows_for_threads(width, cpu_threads);
      session_options.tiled = session_options.band_rows < height;
      session_options.batch.grow_by_rate = true;
      session_options.batch.grow_below = session_options.tiled ? kPassSeconds : kUntiledPassSeconds;
      session_options.batch.first_batch = static_cast<int>(
          std::clamp<int64_t>(kFirstPassPixelSamples / (int64_t(width) * height), 1, 16));
    }
    RenderSession session(renderer, session_options);
    const bool interactive = isatty(STDERR_FILENO);
    ImageMetrics last_metrics;
    double last_report = -1e9;
    // After each step, outside the session's clock: a checkpoint's read-back and metrics are
    // not rendering (and do not eat into --time).
    auto after_step = [&](RenderSession& s) {
      const double elapsed = s.seconds();
      if (log && s.at_checkpoint()) {
        double gpu = renderer.trace_gpu_seconds();
        Image accumulation = renderer.read_accumulation();
        last_metrics = compare_images(accumulation, *reference);
        const ErrorEstimate estimate = renderer.estimate_error();
        char row[288];
        std::snprintf(row, sizeof row, "%lld,%.6f,%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.0f",
                      static_cast<long long>(s.samples()), elapsed, gpu, last_metrics.relmse,
                      estimate.known() ? estimate.relmse : std::nan(""), last_metrics.relmse_trimmed,
                      last_metrics.mape, last_metrics.mean_bias, nonfinite_count(accumulation));
        log->write_line(row);
      }
      if (interactive || elapsed - last_report >= 5.0) {
        std::string line = o.seconds ? format_time_progress(elapsed, *o.seconds, s.samples())
                                     : format_progress(s.traced_samples(), s.options().target.samples, elapsed, "spp");
        // The estimated error beside the bar: the session's own when it targets one, else a
        // fresh one (a small read-back; every 5 s when not on a terminal).
        double estimated = s.estimated_relmse();  // -1: not known (fewer than two samples)
        if (!o.target_error && s.samples() > 0) {
          const ErrorEstimate e = renderer.estimate_error();
          estimated = e.known() ? e.relmse : -1;
        }
        line += format_error_estimate(estimated, o.target_error.value_or(0));
        std::fprintf(stderr, interactive ? "\r%s\033[K" : "%s\n", line.c_str());
        last_report = elapsed;
      }
    };
    while (!session.done()) {
      session.step(long_passes ? kBandSeconds : 0);
      after_step(session);
    }
    double total = session.seconds();
    if (interactive) std::fputc('\n', stderr);
    if (o.target_error) {
      const StopReason why = session.stop_reason();
      std::fprintf(stderr, "glint: stopped by the %s: estimated relMSE %.4g (target %g) at %lld spp, %.2f s\n",
                   stop_reason_text(why), session.estimated_relmse(), *o.target_error,
                   static_cast<long long>(session.samples()), total);
    }
    {
      std::string defines = renderer.last_pass_defines();
      for (char& c : defines) c = c == '\n' ? ' ' : c;
      std::fprintf(stderr, "glint: last pass traced with the %s program%s%s\n",
                   renderer.last_pass_generic() ? "generic" : "specialised",
                   defines.empty() ? "" : ": ", defines.c_str());
    }

    std::string denoise_failure;  // the noisy image is written; the command still fails
    if (o.samples) {
      save_render_part(renderer, part_info(scene, o.estimator, width, height, *o.samples), o.output);
    } else {
      const RenderOutputReport written = save_render_output(renderer, scene.display, o.output, o.output_options);
      if (written.denoised)
        std::fprintf(stderr, "glint: denoised (biased) with Open Image Denoise on the %s in %.2f s\n",
                     written.device.c_str(), written.denoise_seconds);
      if (written.denoise_failed) denoise_failure = written.note;
    }
    if (double discarded = nonfinite_count(renderer.read_accumulation()); discarded > 0)
      std::fprintf(stderr, "warning: %.0f samples were discarded (non-finite, or a BVH traversal past its step cap)\n",
                   discarded);
    double pixel_samples = double(renderer.sample_count()) * width * height;
    std::fprintf(stderr, "glint: wrote %s (%dx%d, %lld spp, %.2f s, %.1f spp/s, %.2f Msamples/s)\n",
                 o.output.c_str(), width, height, static_cast<long long>(renderer.sample_count()), total,
                 renderer.sample_count() / total, pixel_samples / total * 1e-6);
    if (log) {
      log->close();
      std::fprintf(stderr, "glint: wrote %s (last row: relMSE %.4g, trimmed %.4g, bias %+.4g)\n",
                   o.log.c_str(), last_metrics.relmse, last_metrics.relmse_trimmed,
                   last_metrics.mean_bias);
    }
    if (!denoise_failure.empty()) {
      std::fprintf(stderr, "glint render: %s\n", denoise_failure.c_str());
      return 1;
    }
    return 0;
  } catch (const UsageError& e) {  // arguments that conflict with each other or the project
    std::fprintf(stderr, "glint render: %s\n", e.message.c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint render: %s\n", e.what());
    return 1;
  }
}

}  // namespace glint
