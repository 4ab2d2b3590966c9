// A transparent background (RenderOptions::transparent_background, RenderOutputOptions::alpha):
// a white sphere in front of a constant environment (the furnace, where every covered sample is
// exactly the environment's radiance L): coverage 1 at the centre, 0 in the corners, fractional
// on the silhouette; the colour is L premultiplied by it; the PNG and EXR carry it as alpha.
#include <cmath>

#include "renderer/render_output.h"
#include "tests/furnace_scene.h"
#include "tests/gl/gl_test_support.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

constexpr int kSize = 32;
constexpr int kSpp = 64;
// The silhouette's radius in pixels: the sphere (radius 1.5 at distance 5) subtends
// asin(1.5 / 5) from the camera, whose half field of view is 20 degrees over 16 pixels.
const double kSilhouette = std::tan(std::asin(0.3)) / std::tan(glm::radians(20.0)) * kSize / 2;

std::unique_ptr<GpuRenderer> render(TraceBackend backend, bool transparent) {
  GpuRendererOptions options;
  options.backend = backend;
  auto r = std::make_unique<GpuRenderer>(options);
  RenderOptions estimator;
  estimator.transparent_background = transparent;
  r->set_options(estimator);
  r->sync(test::furnace_scene(kSize, kSize), kSize, kSize);
  for (int k : {16, 16, 32}) r->trace(k);
  return r;
}

double distance_from_centre(int x, int y) { return std::hypot(x + 0.5 - kSize / 2.0, y + 0.5 - kSize / 2.0); }

class Coverage : public ::testing::TestWithParam<TraceBackend> {};

TEST_P(Coverage, OneOnTheSphereZeroOnTheEnvironmentFractionalOnItsEdge) {
  test::ensure_gl_context();
  const glm::vec3 L = test::furnace_scene().environment.color;
  for (bool transparent : {true, false}) {
    SCOPED_TRACE(transparent ? "transparent background" : "opaque background");
    auto r = render(GetParam(), transparent);
    ASSERT_EQ(r->sample_count(), kSpp);
    const Image coverage = r->read_coverage(), colour = r->read_accumulation();
    EXPECT_EQ(coverage.at(kSize / 2, kSize / 2)[3], 1.0f);
    EXPECT_EQ(coverage.at(0, 0)[3], 0.0f);
    EXPECT_EQ(coverage.at(kSize - 1, kSize - 1)[3], 0.0f);
    int fractional = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        SCOPED_TRACE(testing::Message() << "pixel " << x << "," << y);
        const float a = coverage.at(x, y)[3];
        const double d = distance_from_centre(x, y);
        if (d < kSilhouette - 1) EXPECT_EQ(a, 1.0f);
        if (d > kSilhouette + 1) EXPECT_EQ(a, 0.0f);
        if (a > 0 && a < 1) {
          ++fractional;
          EXPECT_NEAR(d, kSilhouette, 1.0);
          EXPECT_EQ(a * kSpp, std::round(a * kSpp));  // a count of samples
        }
        // Transparent: the environment seen directly adds nothing, so the mean is L times the
        // coverage; opaque: L everywhere.
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(colour.at(x, y)[c], (transparent ? a : 1.0f) * L[c], 1e-5 * L[c]);
      }
    EXPECT_GT(fractional, 20) << "no antialiased edge";
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, Coverage, ::testing::Values(TraceBackend::fragment, TraceBackend::compute),
                         [](const auto& info) { return std::string(backend_name(info.param)); });

TEST(CoverageOutput, PngHasStraightAlphaExrPremultiplied) {
  test::ensure_gl_context();
  test::TempDir dir;
  auto r = render(TraceBackend::fragment, true);
  const Scene scene = test::furnace_scene(kSize, kSize);
  RenderOutputOptions options;
  options.alpha = true;
  save_render_output(*r, scene.display, dir / "a.exr", options);
  save_render_output(*r, scene.display, dir / "a.png", options);
  save_render_output(*r, scene.display, dir / "opaque.png", {});
  const Image coverage = r->read_coverage(), colour = r->read_accumulation();
  const Image exr = load_image(dir / "a.exr", ColorEncoding::linear);
  const Image png = load_image(dir / "a.png", ColorEncoding::linear);
  const Image opaque = load_image(dir / "opaque.png", ColorEncoding::linear);
  // The display colour of L (straight: the same on the edge as inside).
  const Image inside = tonemapped(Image{1, 1, {0.25f, 0.5f, 1.0f, 1.0f}}, scene.display);
  int edge = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      SCOPED_TRACE(testing::Message() << "pixel " << x << "," << y);
      const float a = coverage.at(x, y)[3];
      EXPECT_EQ(exr.at(x, y)[3], a);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(exr.at(x, y)[c], colour.at(x, y)[c]);  // premultiplied
      EXPECT_NEAR(png.at(x, y)[3], a, 0.5 / 255 + 1e-6);
      if (a > 0)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(png.at(x, y)[c], inside.pixels[c], 1.5 / 255);
      edge += a > 0 && a < 1;
      EXPECT_EQ(opaque.at(x, y)[3], 1.0f);
    }
  EXPECT_GT(edge, 0);
}

}  // namespace
}  // namespace glint
