// The two entry points of the path tracer (renderer/trace_backend.h) give the same image, and
// the automatic choice between them (renderer/backend_choice.h) caches per device.
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <thread>

#include <sys/stat.h>

#include <nlohmann/json.hpp>

#include "renderer/backend_choice.h"
#include "renderer/program_worker.h"
#include "renderer/project_file.h"
#include "tests/gl/gl_test_support.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

// Both run the same function (shaders/lib/sample_accumulation.glsl, add_samples) on the same random
// numbers, compiled by the same driver from the same source except for the entry point, so the
// images agree to rounding: a compiler may contract or reorder a few float operations
// differently in the two programs. A rounding difference can in principle flip a branch (a ray
// that grazes an edge), which changes that pixel by a whole sample, so this is a bound on the
// colour channels' relative difference per pixel (at least 1e-3 absolute, as in
// max_relative_difference) with a margin far above float rounding (1e-7) and far below a
// changed sample (of order 1 / spp = 0.17 here).
constexpr double kTolerance = 1e-4;

// 21x13: neither side a multiple of the 8x8 work group, so the last groups overhang the image.
constexpr int kWidth = 21, kHeight = 13;

Image render(GpuRenderer& r, const Scene& scene, SamplerKind sampler) {
  RenderOptions options;
  options.sampler = sampler;
  r.set_options(options);
  r.sync(scene, kWidth, kHeight);
  // Several passes of different sizes: the compute path reads and writes its accumulation in
  // place, the fragment path ping-pongs.
  for (int k : {1, 2, 3}) r.trace(k);
  return r.read_accumulation();
}

std::unique_ptr<GpuRenderer> make_renderer(TraceBackend backend, bool generic) {
  GpuRendererOptions options;
  options.backend = backend;
  options.force_generic_shader = generic;
  return std::make_unique<GpuRenderer>(options);
}

TEST(GlBackends, SameImageForEveryExampleProjectAndSampler) {
  test::ensure_gl_context();
  auto fragment = make_renderer(TraceBackend::fragment, true);
  auto compute = make_renderer(TraceBackend::compute, true);
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(GLINT_SOURCE_DIR "/projects")) {
    if (entry.path().extension() != ".glint") continue;
    const Scene scene = load_project(entry.path());
    for (SamplerKind sampler : {SamplerKind::pcg, SamplerKind::sobol}) {
      SCOPED_TRACE(entry.path().filename().string() + (sampler == SamplerKind::pcg ? " pcg" : " sobol"));
      const Image a = render(*fragment, scene, sampler);
      const Image b = render(*compute, scene, sampler);
      ASSERT_EQ(fragment->sample_count(), 6);
      ASSERT_EQ(compute->sample_count(), 6);
      EXPECT_TRUE(test::all_finite(b));
      EXPECT_LE(test::max_relative_difference(b, a), kTolerance);
      double sum = 0;
      for (size_t i = 0; i < a.pixels.size(); ++i) {
        if (i % 4 != 3) sum += a.pixels[i];
        else EXPECT_EQ(a.pixels[i], b.pixels[i]) << "discarded-sample counts differ";
      }
      EXPECT_GT(sum, 0.0) << "black image: nothing compared";
      const Image da = fragment->read_display(), db = compute->read_display();
      EXPECT_LE(test::max_relative_difference(db, da), kTolerance) << "tonemapped";
    }
    ++count;
  }
  EXPECT_GE(count, 6);
}

// The specialised programs (built for the scene's features) agree as well, and the compute
// path actually ran them.
TEST(GlBackends, SameImageWithSpecialisedPrograms) {
  test::ensure_gl_context();
  const Scene scene = load_project(GLINT_SOURCE_DIR "/projects/cornell_box.glint");
  auto fragment = make_renderer(TraceBackend::fragment, false);
  auto compute = make_renderer(TraceBackend::compute, false);
  Image images[2];
  GpuRenderer* renderers[2] = {fragment.get(), compute.get()};
  for (int i = 0; i < 2; ++i) {
    GpuRenderer& r = *renderers[i];
    r.sync(scene, kWidth, kHeight);
    r.prepare_specialised_program();
    for (int k : {2, 3}) r.trace(k);
    EXPECT_FALSE(r.last_pass_generic());
    images[i] = r.read_accumulation();
  }
  EXPECT_EQ(compute->backend(), TraceBackend::compute);
  EXPECT_LE(test::max_relative_difference(images[1], images[0]), kTolerance);
}

// The compute path's specialised program built on the worker thread (renderer/program_worker.h):
// the passes switch to it once it is ready, and the image is still the fragment path's.
TEST(GlBackends, ComputeVariantBuiltOnTheWorker) {
  HeadlessGLContext& main = test::ensure_gl_context();
  std::unique_ptr<HeadlessGLContext> shared = main.create_shared();
  auto worker = std::make_shared<ProgramWorker>(SharedContextHooks{
      [&] { shared->make_current(); }, [&] { shared->release_current(); }});
  const Scene scene = load_project(GLINT_SOURCE_DIR "/projects/roughness_ladder.glint");
  GpuRendererOptions options;
  options.backend = TraceBackend::compute;
  options.worker = worker;
  GpuRenderer compute(options);
  compute.sync(scene, kWidth, kHeight);
  const auto start = std::chrono::steady_clock::now();
  // Without Mesa's shader cache the worker's build takes several seconds (its probes compile
  // the program again, renderer/program_worker.cpp); the generic program traces meanwhile.
  auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  while (seconds() < 120) {
    compute.trace(1);
    if (!compute.last_pass_generic()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_FALSE(compute.last_pass_generic()) << "no specialised pass within " << seconds() << " s";
  auto fragment = make_renderer(TraceBackend::fragment, true);
  fragment->sync(scene, kWidth, kHeight);
  for (int64_t n = compute.sample_count(); n > 0; n -= 1) fragment->trace(1);
  EXPECT_LE(test::max_relative_difference(compute.read_accumulation(), fragment->read_accumulation()),
            kTolerance);
  worker.reset();
}

nlohmann::json read_json(const std::filesystem::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in, nullptr, false);
}

TEST(GlBackendChoice, WritesItsCacheAndReadsItWithoutTiming) {
  test::ensure_gl_context();
  test::TempDir dir;
  const auto file = dir / "glint" / "backend.json";
  const BackendChoice first = choose_backend(file);
  EXPECT_FALSE(first.from_cache);
  EXPECT_TRUE(first.note.empty()) << first.note;
  EXPECT_GT(first.fragment_spp_s, 0);
  EXPECT_GT(first.compute_spp_s, 0);
  EXPECT_EQ(first.backend, prefers_compute({first.fragment_spp_s, first.compute_spp_s})
                               ? TraceBackend::compute
                               : TraceBackend::fragment);
  const nlohmann::json cache = read_json(file);
  ASSERT_TRUE(cache.is_object());
  EXPECT_EQ(cache["devices"][device_key()]["backend"], backend_name(first.backend));

  const BackendChoice second = choose_backend(file);
  EXPECT_TRUE(second.from_cache);
  EXPECT_EQ(second.backend, first.backend);
  EXPECT_EQ(second.fragment_spp_s, first.fragment_spp_s);
  EXPECT_LT(second.seconds, first.seconds);

  // What the cache says wins, whatever timing would say: the entry is read, not re-measured.
  // Other devices' entries are kept when an entry is added.
  const std::string edited = R"({"devices": {")" + device_key() +
                             R"(": {"backend": "compute", "fragment_spp_s": 1, "compute_spp_s": 2},
                                    "Other | GPU | 1.0": {"backend": "fragment"}}})";
  std::ofstream(file) << edited;
  const BackendChoice third = choose_backend(file);
  EXPECT_TRUE(third.from_cache);
  EXPECT_EQ(third.backend, TraceBackend::compute);
  EXPECT_EQ(third.fragment_spp_s, 1);
}

TEST(GlBackendChoice, CorruptOrUnwritableCacheStillGivesAChoice) {
  test::ensure_gl_context();
  test::TempDir dir;
  const auto file = dir / "backend.json";
  std::ofstream(file) << "{\"devices\": [1, 2";  // cut short
  const BackendChoice corrupt = choose_backend(file);
  EXPECT_FALSE(corrupt.from_cache);
  EXPECT_NE(corrupt.note.find("unreadable backend cache"), std::string::npos) << corrupt.note;
  const nlohmann::json replaced = read_json(file);  // timed again and replaced
  ASSERT_TRUE(replaced.is_object());
  EXPECT_EQ(replaced["devices"][device_key()]["backend"], backend_name(corrupt.backend));

  // A folder that cannot be made (its parent is a file): timed, not written, one note.
  std::ofstream(dir / "a_file") << "x";
  const BackendChoice unwritable = choose_backend(dir / "a_file" / "glint" / "backend.json");
  EXPECT_FALSE(unwritable.from_cache);
  EXPECT_NE(unwritable.note.find("backend cache not written"), std::string::npos) << unwritable.note;
  EXPECT_EQ(unwritable.note.find('\n'), std::string::npos);
}

// The cache is untrusted: a FIFO (which would block a plain read), a folder, a mistyped field
// and a link planted at its path are each treated as no cache and timed again; a FIFO, folder
// or link is left as it is (nothing is written through the link or over the FIFO), a bad
// entry is repaired.
TEST(GlBackendChoice, HostileCacheFilesAreTimedAgainAndNeverWrittenThrough) {
  test::ensure_gl_context();
  test::TempDir dir;
  const auto fifo = dir / "fifo.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const BackendChoice from_fifo = choose_backend(fifo);
  EXPECT_FALSE(from_fifo.from_cache);
  EXPECT_NE(from_fifo.note.find(fifo.string()), std::string::npos) << from_fifo.note;
  EXPECT_NE(from_fifo.note.find("FIFO"), std::string::npos) << from_fifo.note;
  EXPECT_TRUE(fs::is_fifo(fifo));

  const auto mistyped = dir / "mistyped.json";
  std::ofstream(mistyped) << R"({"devices": {")" + device_key() +
                                 R"(": {"backend": "compute", "fragment_spp_s": "fast", "compute_spp_s": 2}}})";
  const BackendChoice repaired = choose_backend(mistyped);
  EXPECT_FALSE(repaired.from_cache);
  EXPECT_NE(repaired.note.find("mistyped"), std::string::npos) << repaired.note;
  EXPECT_TRUE(read_json(mistyped)["devices"][device_key()]["fragment_spp_s"].is_number());
  EXPECT_TRUE(choose_backend(mistyped).from_cache);

  const auto target = dir / "precious.txt";
  std::ofstream(target) << "not Glint's";
  const auto link = dir / "link.json";
  fs::create_symlink(target, link);
  const BackendChoice through_link = choose_backend(link);
  EXPECT_FALSE(through_link.from_cache);
  EXPECT_NE(through_link.note.find("symbolic link"), std::string::npos) << through_link.note;
  EXPECT_TRUE(fs::is_symlink(link));
  std::ifstream in(target);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "not Glint's");
}

TEST(GlBackendChoice, ComputeOnlyWhenClearlyFaster) {
  EXPECT_FALSE(prefers_compute({100, 100}));
  EXPECT_FALSE(prefers_compute({100, 109}));  // within the margin: the fragment path stays
  EXPECT_TRUE(prefers_compute({100, 111}));
  EXPECT_TRUE(prefers_compute({60, 1800}));
  EXPECT_FALSE(prefers_compute({1800, 60}));
}

// 64x64 tiles, whole or part: one tile for an image of up to 64x64, then a tile per started 64.
TEST(GlBackendChoice, SmallImagesCountTheirLlvmpipeTiles) {
  EXPECT_TRUE(fewer_llvmpipe_tiles_than_threads(64, 64, 2));    // one tile
  EXPECT_TRUE(fewer_llvmpipe_tiles_than_threads(24, 18, 2));
  EXPECT_FALSE(fewer_llvmpipe_tiles_than_threads(65, 64, 2));   // two tiles
  EXPECT_FALSE(fewer_llvmpipe_tiles_than_threads(128, 128, 2));
  EXPECT_TRUE(fewer_llvmpipe_tiles_than_threads(128, 128, 16));  // four tiles
  EXPECT_FALSE(fewer_llvmpipe_tiles_than_threads(256, 256, 16));  // sixteen
  EXPECT_FALSE(fewer_llvmpipe_tiles_than_threads(64, 64, 1));
}

TEST(GlBackendChoice, CacheFileFollowsXdgCacheHomeThenHome) {
  test::TempDir dir;
  auto saved = [](const char* name) -> std::optional<std::string> {
    const char* v = std::getenv(name);
    return v ? std::optional<std::string>(v) : std::nullopt;
  };
  const auto xdg = saved("XDG_CACHE_HOME"), home = saved("HOME");
  setenv("XDG_CACHE_HOME", (dir / "xdg").c_str(), 1);
  setenv("HOME", (dir / "home").c_str(), 1);
  EXPECT_EQ(default_backend_cache_file(), dir / "xdg" / "glint" / "backend.json");
  unsetenv("XDG_CACHE_HOME");
  EXPECT_EQ(default_backend_cache_file(), dir / "home" / ".cache" / "glint" / "backend.json");
  // A relative XDG_CACHE_HOME is ignored, as the XDG Base Directory specification says (it
  // would put the cache in whatever folder a render starts in).
  setenv("XDG_CACHE_HOME", "relative/cache", 1);
  EXPECT_EQ(default_backend_cache_file(), dir / "home" / ".cache" / "glint" / "backend.json");
  unsetenv("XDG_CACHE_HOME");
  unsetenv("HOME");
  EXPECT_EQ(default_backend_cache_file(), std::nullopt);
  if (xdg) setenv("XDG_CACHE_HOME", xdg->c_str(), 1);
  if (home) setenv("HOME", home->c_str(), 1);
}

}  // namespace
}  // namespace glint
