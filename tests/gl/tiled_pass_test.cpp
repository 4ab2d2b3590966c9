// A pass traced in bands of rows (GpuRenderer::begin_pass, trace_rows) gives the image that
// the same pass traced in one go gives, on both entry points, with either sampler and with
// adaptive sampling; a tiled RenderSession renders the image an untiled one does.
#include <algorithm>
#include <stdexcept>
#include <vector>

#include "renderer/loop_budget.h"
#include "renderer/project_file.h"
#include "renderer/render_session.h"
#include "tests/gl/gl_test_support.h"

namespace glint {
namespace {

// 21x13: odd, neither side a multiple of the compute path's 8x8 work group, so a band's last
// groups overhang both the band and the image.
constexpr int kWidth = 21, kHeight = 13;

// Passes of different sizes; 7 is more than one draw of the deep scene below.
const std::vector<int> kPasses = {1, 7, 2, 5, 3};

struct Variant {
  TraceBackend backend;
  SamplerKind sampler;
  bool adaptive;
};

std::unique_ptr<GpuRenderer> make_renderer(TraceBackend backend) {
  GpuRendererOptions options;
  options.backend = backend;
  // One program for every pass of both renders: a specialised one would replace the generic
  // one after a compile whose end depends on timing, and the two differ by rounding.
  options.force_generic_shader = true;
  return std::make_unique<GpuRenderer>(options);
}

void prepare(GpuRenderer& r, const Scene& scene, const Variant& v) {
  RenderOptions options;
  options.sampler = v.sampler;
  options.adaptive = v.adaptive;
  // Small, so that pixels start waiting within these few passes.
  options.adaptive_min_samples = 2;
  options.adaptive_every = 3;
  r.set_options(options);
  r.set_aovs_enabled(true);
  r.sync(scene, kWidth, kHeight);
}

// The passes in bands of `rows` rows (the last band of each pass what is left).
void trace_in_bands(GpuRenderer& r, int rows) {
  for (int k : kPasses) {
    r.begin_pass(k);
    int bands = 0;
    while (r.pass_under_way()) {
      EXPECT_EQ(r.pass_samples(), k);
      const int left = r.pass_rows_left();
      EXPECT_EQ(r.trace_rows(rows), std::min(rows, left));
      ++bands;
    }
    EXPECT_EQ(bands, (kHeight + rows - 1) / rows);
  }
}

// Everything the pass writes: colour, discarded-sample counts, variances and per-pixel sample
// counts, the auxiliary images; compared as floats, exactly.
void expect_same_images(GpuRenderer& a, GpuRenderer& b) {
  ASSERT_EQ(a.sample_count(), b.sample_count());
  EXPECT_EQ(a.read_accumulation().pixels, b.read_accumulation().pixels) << "accumulation";
  EXPECT_EQ(a.read_variance().pixels, b.read_variance().pixels) << "variance and sample counts";
  const AovImages aa = a.read_aovs(), ab = b.read_aovs();
  EXPECT_EQ(aa.albedo.pixels, ab.albedo.pixels) << "albedo";
  EXPECT_EQ(aa.normal.pixels, ab.normal.pixels) << "normal";
  EXPECT_EQ(a.read_display().pixels, b.read_display().pixels) << "display";
}

// A few shapes and 64 bounces: more loop iterations per sample than a single draw of 7 samples
// may run on llvmpipe, so the renderer splits those passes into draws (loop_budget.h), and a
// band takes several draws.
Scene deep_scene() {
  Scene s = test::empty_scene();
  s.environment.color = {0.6f, 0.7f, 0.9f};
  s.render.max_bounces = 64;
  s.materials.push_back({.name = "white", .color = {0.9f, 0.9f, 0.9f}});
  s.materials.push_back({.name = "lamp", .color = {0, 0, 0}, .emission = {4, 4, 4}});
  s.spheres.push_back({.name = "a", .center = {-0.8f, 0, 0}, .radius = 0.7f, .material = "white"});
  s.spheres.push_back({.name = "b", .center = {0.8f, 0, 0}, .radius = 0.7f, .material = "white"});
  s.spheres.push_back({.name = "lamp", .center = {0, 1.6f, 0}, .radius = 0.3f, .material = "lamp"});
  return s;
}

TEST(TiledPass, SameImageAsOnePassOnBothBackendsSamplersAndWithAdaptiveSampling) {
  test::ensure_gl_context();
  ASSERT_LT(samples_per_draw_for(loop_iterations_per_sample(3, 64)), 7) << "no pass of several draws";
  const Scene scenes[2] = {load_project(GLINT_SOURCE_DIR "/projects/cornell_box.glint"), deep_scene()};
  for (TraceBackend backend : {TraceBackend::fragment, TraceBackend::compute}) {
    auto whole = make_renderer(backend);
    auto banded = make_renderer(backend);
    for (const Scene& scene : scenes)
      for (const Variant v : {Variant{backend, SamplerKind::sobol, false}, Variant{backend, SamplerKind::pcg, false},
                              Variant{backend, SamplerKind::sobol, true}})
        for (int rows : {1, 4, kHeight - 1}) {
          SCOPED_TRACE(std::string(backend_name(backend)) + (v.sampler == SamplerKind::pcg ? " pcg" : " sobol") +
                       (v.adaptive ? " adaptive" : "") + " scene with " +
                       std::to_string(scene.spheres.size()) + " spheres, bands of " + std::to_string(rows));
          prepare(*whole, scene, v);
          prepare(*banded, scene, v);
          ASSERT_FALSE(whole->uses_bvh());
          for (int k : kPasses) whole->trace(k);
          trace_in_bands(*banded, rows);
          expect_same_images(*whole, *banded);
          const Image image = whole->read_accumulation();
          EXPECT_TRUE(test::all_finite(image));
          if (v.adaptive) {
            // Some pixel waited in some pass: adaptive sampling did change the passes.
            const Image counts = whole->read_variance();
            float fewest = 1e9f;
            for (size_t i = 3; i < counts.pixels.size(); i += 4) fewest = std::min(fewest, counts.pixels[i]);
            EXPECT_LT(fewest, float(whole->sample_count())) << "no pixel waited";
          }
        }
  }
}

TEST(TiledPass, APassIsOneUnitForTheSampleCountAndASyncAbandonsIt) {
  test::ensure_gl_context();
  GpuRenderer r;
  r.sync(deep_scene(), kWidth, kHeight);
  r.trace(2);
  r.begin_pass(3);
  EXPECT_THROW(r.begin_pass(1), std::logic_error);
  EXPECT_THROW(r.trace(1), std::logic_error);
  EXPECT_EQ(r.trace_rows(5), 5);
  EXPECT_EQ(r.sample_count(), 2) << "a pass counts once it has ended";
  EXPECT_EQ(r.pass_rows_left(), kHeight - 5);
  EXPECT_EQ(r.trace_rows(100), kHeight - 5);
  EXPECT_FALSE(r.pass_under_way());
  EXPECT_EQ(r.sample_count(), 5);
  EXPECT_EQ(r.trace_rows(1), 0) << "no pass under way";

  r.begin_pass(3);
  r.trace_rows(2);
  Scene moved = deep_scene();
  moved.camera.position.x += 0.1f;
  EXPECT_TRUE(r.sync(moved, kWidth, kHeight).accumulation_reset);
  EXPECT_FALSE(r.pass_under_way());
  EXPECT_EQ(r.sample_count(), 0);
  r.begin_pass(0);  // no samples: no pass
  EXPECT_FALSE(r.pass_under_way());
}

// The same passes (a batch that never grows: one sample each) tiled and untiled: the same image.
// A budget below any row's time makes every step trace exactly one row.
TEST(TiledPass, TiledSessionStepsARowAtATimeAndRendersTheSameImage) {
  test::ensure_gl_context();
  const Scene scene = load_project(GLINT_SOURCE_DIR "/projects/cornell_box.glint");
  auto whole = make_renderer(TraceBackend::fragment);
  auto banded = make_renderer(TraceBackend::fragment);
  whole->sync(scene, kWidth, kHeight);
  banded->sync(scene, kWidth, kHeight);
  RenderSessionOptions o;
  o.target.samples = 3;
  o.batch.grow_below = 0;
  RenderSession untiled(*whole, o);
  untiled.run();
  o.tiled = true;
  RenderSession tiled(*banded, o);
  int steps = 0;
  std::vector<float> progress;
  while (!tiled.done()) {
    const int64_t added = tiled.step(1e-9);
    ++steps;
    EXPECT_EQ(tiled.step_pixel_samples(), kWidth) << "one row of one sample, step " << steps;
    EXPECT_EQ(added, steps % kHeight == 0 ? 1 : 0) << "a pass counts when its last row is traced";
    progress.push_back(tiled.progress());
  }
  EXPECT_EQ(steps, 3 * kHeight);
  EXPECT_TRUE(std::is_sorted(progress.begin(), progress.end()));
  EXPECT_LT(progress.front(), 1.0f / 3 / kHeight + 1e-6f);
  EXPECT_EQ(tiled.stop_reason(), StopReason::samples);
  expect_same_images(*whole, *banded);
}

// Bands of a multiple of band_rows rows (the pass's last band excepted), even when the
// budget fits less than one row; traced_samples() counts the rows of a pass under way.
TEST(TiledPass, BandsAreMultiplesOfBandRows) {
  test::ensure_gl_context();
  static_assert(kHeight % 3 != 0, "the last band must be shorter");
  GpuRenderer r;
  r.sync(load_project(GLINT_SOURCE_DIR "/projects/cornell_box.glint"), kWidth, kHeight);
  RenderSessionOptions o;
  o.target.samples = 2;
  o.batch = {.first_batch = 2, .max_batch = 2};
  o.tiled = true;
  o.band_rows = 3;
  RenderSession session(r, o);
  std::vector<int64_t> rows;
  while (!session.done()) {
    session.step(1e-9);
    rows.push_back(session.step_pixel_samples() / (2 * kWidth));
    if (!session.done()) {
      EXPECT_DOUBLE_EQ(session.traced_samples(), 2.0 * (kHeight - r.pass_rows_left()) / kHeight);
    }
  }
  std::vector<int64_t> expected(kHeight / 3, 3);
  expected.push_back(kHeight % 3);
  EXPECT_EQ(rows, expected);
  EXPECT_EQ(session.traced_samples(), 2.0);
}

// Bands of whole 64-row tile rows with at least four tiles per thread.
TEST(TiledPass, BandRowsHoldFourTilesPerThread) {
  EXPECT_EQ(band_rows_for_threads(128, 2), 256);   // two tiles a row: four rows of tiles
  EXPECT_EQ(band_rows_for_threads(512, 2), 64);    // eight tiles a row
  EXPECT_EQ(band_rows_for_threads(1920, 16), 192);  // 30 tiles a row, 64 wanted
  EXPECT_EQ(band_rows_for_threads(64, 0), 256);    // an unknown thread count counts as one
}

// A time target is checked between passes only: a tiled session never stops within a pass,
// whose rows are part-traced (and, on the compute path, part-written in place).
TEST(TiledPass, TimeTargetEndsAfterAWholePass) {
  test::ensure_gl_context();
  GpuRenderer r;
  r.sync(deep_scene(), kWidth, kHeight);
  RenderSessionOptions o;
  o.target = {.samples = 0, .seconds = 1e-9};
  o.tiled = true;
  RenderSession session(r, o);
  int steps = 0;
  while (!session.done()) {
    session.step(1e-9);
    ++steps;
  }
  EXPECT_EQ(steps, kHeight);
  EXPECT_EQ(session.stop_reason(), StopReason::time);
  EXPECT_EQ(r.sample_count(), 1);
  EXPECT_FALSE(r.pass_under_way());
}

}  // namespace
}  // namespace glint
