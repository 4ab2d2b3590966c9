// Region render (GpuRenderer::set_sample_region): in both back ends, pixels outside the region
// receive no samples and keep what they held; pixels inside get exactly the samples a render
// of the whole image gives them. And the live error map (renderer/error_map.h) shows each
// pixel's estimated relMSE.
#include <cmath>

#include "renderer/error_map.h"
#include "renderer/project_file.h"
#include "renderer/sample_region.h"
#include "tests/furnace_scene.h"
#include "tests/gl/gl_test_support.h"

namespace glint {
namespace {

constexpr int kWidth = 21, kHeight = 13;  // not multiples of the compute shader's 8x8 groups
const PixelRect kRegion{5, 3, 14, 9};

std::unique_ptr<GpuRenderer> make_renderer(TraceBackend backend) {
  GpuRendererOptions options;
  options.backend = backend;
  return std::make_unique<GpuRenderer>(options);
}

// The samples each pixel has taken (read_variance's a).
float taken(const Image& variance, int x, int y) { return variance.at(x, y)[3]; }

class SampleRegion : public ::testing::TestWithParam<TraceBackend> {};

TEST_P(SampleRegion, PixelsOutsideTheRegionReceiveNoSamples) {
  test::ensure_gl_context();
  const Scene scene = test::furnace_scene(kWidth, kHeight);
  auto whole = make_renderer(GetParam());
  whole->sync(scene, kWidth, kHeight);
  for (int k : {1, 2, 3}) whole->trace(k);
  const Image reference = whole->read_accumulation();

  auto r = make_renderer(GetParam());
  r->sync(scene, kWidth, kHeight);
  r->set_sample_region(kRegion);
  for (int k : {1, 2, 3}) r->trace(k);
  EXPECT_EQ(r->sample_count(), 6);
  const Image mean = r->read_accumulation(), variance = r->read_variance();
  int inside = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      SCOPED_TRACE(testing::Message() << "pixel " << x << "," << y);
      if (kRegion.contains(x, y)) {
        ++inside;
        EXPECT_EQ(taken(variance, x, y), 6.0f);
        for (int c = 0; c < 3; ++c) EXPECT_EQ(mean.at(x, y)[c], reference.at(x, y)[c]);
      } else {
        EXPECT_EQ(taken(variance, x, y), 0.0f);
        for (int c = 0; c < 4; ++c) EXPECT_EQ(mean.at(x, y)[c], 0.0f);
      }
    }
  EXPECT_EQ(inside, 9 * 6);
}

// A region drawn over a running render: no reset; the pixels outside keep their samples and
// their mean, those inside go on from their own count; cleared, every pixel goes on again.
TEST_P(SampleRegion, ARegionOverARunningRenderFreezesTheRest) {
  test::ensure_gl_context();
  const Scene scene = test::furnace_scene(kWidth, kHeight);
  auto r = make_renderer(GetParam());
  r->sync(scene, kWidth, kHeight);
  r->trace(2);
  const Image before = r->read_accumulation();
  r->set_sample_region(kRegion);
  EXPECT_FALSE(r->sync(scene, kWidth, kHeight).accumulation_reset);
  r->trace(3);
  const Image frozen = r->read_accumulation(), counts = r->read_variance();
  EXPECT_EQ(taken(counts, 0, 0), 2.0f);
  EXPECT_EQ(taken(counts, kRegion.x0, kRegion.y0), 5.0f);
  for (int c = 0; c < 4; ++c) EXPECT_EQ(frozen.at(20, 12)[c], before.at(20, 12)[c]);
  r->set_sample_region(std::nullopt);
  r->trace(1);
  const Image after = r->read_variance();
  EXPECT_EQ(taken(after, 0, 0), 3.0f);
  EXPECT_EQ(taken(after, kRegion.x0, kRegion.y0), 6.0f);
  EXPECT_EQ(r->sample_count(), 6);  // the most any pixel has taken
  // A reset (the camera moved) makes the counts uniform again.
  Scene moved = scene;
  moved.camera.position.x += 0.1f;
  EXPECT_TRUE(r->sync(moved, kWidth, kHeight).accumulation_reset);
  r->trace(2);
  EXPECT_EQ(taken(r->read_variance(), 0, 0), 2.0f);
}

INSTANTIATE_TEST_SUITE_P(Backends, SampleRegion, ::testing::Values(TraceBackend::fragment, TraceBackend::compute),
                         [](const auto& info) { return std::string(backend_name(info.param)); });

TEST(SampleRegionPixels, FractionsCoverEveryTouchedPixel) {
  EXPECT_EQ(region_pixels({0.25f, 0.5f, 0.5f, 1.0f}, 8, 4), (PixelRect{2, 2, 4, 4}));
  EXPECT_EQ(region_pixels({0.5f, 1.0f, 0.26f, 0.5f}, 8, 4), (PixelRect{2, 2, 4, 4}));  // any corner order
  EXPECT_EQ(region_pixels({0.3f, 0.3f, 0.31f, 0.31f}, 8, 4), (PixelRect{2, 1, 3, 2}));  // at least one
  EXPECT_EQ(region_pixels({-1, -1, 2, 2}, 8, 4), (PixelRect{0, 0, 8, 4}));             // clipped
  EXPECT_FALSE(region_pixels({1.2f, 0, 1.5f, 1}, 8, 4));                               // outside
  EXPECT_FALSE(region_pixels({0.5f, 0, 0.5f, 1}, 8, 4));                               // no area
  EXPECT_FALSE(region_pixels({NAN, 0, 1, 1}, 8, 4));
  EXPECT_FALSE(region_pixels({0, 0, 1, 1}, 0, 4));
}

// The map's colour of each pixel is the heat colour of the relMSE that the error estimate
// computes for it (lib/error_estimate.glsl), from the same textures; no estimate, no colour.
TEST(ErrorMap, ShowsEachPixelsEstimatedError) {
  test::ensure_gl_context();
  const Scene scene = load_project(GLINT_SOURCE_DIR "/projects/default.glint");  // noisy everywhere
  auto r = make_renderer(TraceBackend::fragment);
  r->sync(scene, kWidth, kHeight);
  r->set_sample_region(kRegion);
  r->trace(4);
  const GLuint map = r->error_map();
  ASSERT_NE(map, 0u);
  EXPECT_EQ(r->error_map(), map);  // unchanged accumulation: not drawn again
  std::vector<unsigned char> rgba(size_t(kWidth) * kHeight * 4);
  glGetTextureImage(map, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(rgba.size()), rgba.data());
  const Image mean = r->read_accumulation(), variance = r->read_variance();
  int coloured = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      SCOPED_TRACE(testing::Message() << "pixel " << x << "," << y);
      const unsigned char* p = &rgba[(size_t(y) * kWidth + x) * 4];
      if (!kRegion.contains(x, y)) {  // no samples: no estimate
        EXPECT_EQ(p[3], 0);
        continue;
      }
      const float n = variance.at(x, y)[3] - mean.at(x, y)[3];
      double r_sum = 0;
      for (int c = 0; c < 3; ++c)
        r_sum += variance.at(x, y)[c] / (n - 1) / (double(mean.at(x, y)[c]) * mean.at(x, y)[c] + 0.01);
      const glm::vec3 expected = error_map_colour(float(r_sum / 3));
      EXPECT_NEAR(p[3], kErrorMapOpacity * 255, 1);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[c], expected[c] * 255, 3);
      coloured += expected != error_map_colour(0.0f);
    }
  EXPECT_GT(coloured, 0) << "every pixel without noise: nothing compared";
  // Cold below the scale, hot above it.
  EXPECT_EQ(error_map_colour(1e-9f), error_map_colour(kErrorMapLow));
  EXPECT_EQ(error_map_colour(1e3f), error_map_colour(kErrorMapHigh));
  EXPECT_GT(error_map_colour(kErrorMapHigh).r, error_map_colour(kErrorMapLow).r);
}

}  // namespace
}  // namespace glint
