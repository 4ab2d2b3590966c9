// Sample ranges on the GPU (RenderOptions::first_sample): parts rendered separately and merged
// (renderer/part_merge.h) give the single render of all their samples, for both samplers.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "gl_test_support.h"
#include "renderer/part_merge.h"
#include "renderer/project_file.h"
#include "renderer/render_part.h"

namespace glint {
namespace {

constexpr int kWidth = 16, kHeight = 12;

// The parts take exactly the samples of the single render, so the only difference is float32
// rounding: each of the 1 + 3 accumulations is a compensated running mean within a few ulps
// (2^-24 = 6e-8 relative) of its samples' exact mean, and the merge adds them in double. 1e-5
// relative (about 170 ulps, at least 1e-3 absolute as in max_relative_difference) bounds that
// with a wide margin; one different sample in a pixel of 12 changes it by of order 1/12 of the
// spread of its samples (GlRenderParts.WrongOffsetIsFarFromTheSingleRender measures it).
constexpr double kTolerance = 1e-5;

Image render(GpuRenderer& r, const Scene& scene, SamplerKind sampler, SampleRange range) {
  RenderOptions options;
  options.sampler = sampler;
  options.first_sample = static_cast<uint32_t>(range.first);
  r.set_options(options);
  r.sync(scene, 1, 1);  // another size first: a fresh accumulation even when nothing else changed
  r.sync(scene, kWidth, kHeight);
  // Passes of 1, 2, 3, ... samples: a part's passes split its samples differently from the
  // single render's.
  for (int64_t done = 0, k = 1; done < range.count(); done += k, ++k) {
    k = std::min(k, range.count() - done);
    r.trace(static_cast<int>(k));
  }
  EXPECT_EQ(r.sample_count(), range.count());
  return r.read_accumulation();
}

Image merged(GpuRenderer& r, const Scene& scene, SamplerKind sampler, const std::vector<SampleRange>& ranges,
             bool offset) {
  std::vector<RenderPart> parts;
  for (const SampleRange& range : ranges) {
    RenderPart p;
    p.info.width = kWidth;
    p.info.height = kHeight;
    p.info.range = range;
    p.image = render(r, scene, sampler, offset ? range : SampleRange{0, range.count()});
    parts.push_back(std::move(p));
  }
  return merge_part_images(parts);
}

std::unique_ptr<GpuRenderer> generic_renderer() {
  GpuRendererOptions options;
  options.force_generic_shader = true;  // one program throughout: no switch mid-render
  return std::make_unique<GpuRenderer>(options);
}

std::string format_difference(double d) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", d);
  return text;
}

const std::vector<SampleRange> kRanges = {{0, 5}, {5, 9}, {9, 12}};

TEST(GlRenderParts, MergedPartsEqualTheSingleRender) {
  test::ensure_gl_context();
  auto r = generic_renderer();
  const Scene scene = load_project(GLINT_SOURCE_DIR "/projects/cornell_box.glint");
  for (SamplerKind sampler : {SamplerKind::pcg, SamplerKind::sobol}) {
    SCOPED_TRACE(sampler == SamplerKind::pcg ? "pcg" : "sobol");
    const Image single = render(*r, scene, sampler, {0, 12});
    const Image parts = merged(*r, scene, sampler, kRanges, true);
    const double d = test::max_relative_difference(parts, single);
    EXPECT_LE(d, kTolerance);
    RecordProperty(sampler == SamplerKind::pcg ? "pcg_max_relative_difference" : "sobol_max_relative_difference",
                   format_difference(d));
    for (size_t i = 3; i < single.pixels.size(); i += 4) ASSERT_EQ(parts.pixels[i], single.pixels[i]);
  }
}

// The check above could fail: parts that all start at sample 0 repeat samples instead of
// taking the single render's, and differ from it far beyond the tolerance.
TEST(GlRenderParts, WrongOffsetIsFarFromTheSingleRender) {
  test::ensure_gl_context();
  auto r = generic_renderer();
  const Scene scene = load_project(GLINT_SOURCE_DIR "/projects/cornell_box.glint");
  const Image single = render(*r, scene, SamplerKind::sobol, {0, 12});
  const Image wrong = merged(*r, scene, SamplerKind::sobol, kRanges, false);
  const double d = test::max_relative_difference(wrong, single);
  EXPECT_GT(d, 100 * kTolerance);
  RecordProperty("max_relative_difference", format_difference(d));
}

}  // namespace
}  // namespace glint
