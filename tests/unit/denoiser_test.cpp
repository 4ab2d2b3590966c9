// The denoiser's round trip on a tiny image (renderer/denoiser.h). Where the build bundled Open
// Image Denoise (GLINT_OIDN_BUNDLED: the wheel was there, as in CI) it must load and run; in a
// build without it the tests are skipped and say why.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "renderer/denoiser.h"

namespace glint {
namespace {

bool skip_without_library() {
  const auto why = denoising_unavailable();
  if (!why) return false;
  if (GLINT_OIDN_BUNDLED) ADD_FAILURE() << "the build bundled Open Image Denoise but it did not load: " << *why;
  return true;
}

Image filled(int w, int h, float r, float g, float b) {
  Image image;
  image.width = w;
  image.height = h;
  image.pixels.resize(static_cast<size_t>(w) * h * 4);
  for (size_t i = 0; i < image.pixels.size(); i += 4) {
    image.pixels[i] = r, image.pixels[i + 1] = g, image.pixels[i + 2] = b, image.pixels[i + 3] = 1;
  }
  return image;
}

double squared_error(const Image& a, float value) {
  double sum = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    if (i % 4 != 3) sum += (a.pixels[i] - value) * (a.pixels[i] - value);
  return sum;
}

// A flat grey surface (albedo 0.5, one normal) rendered with noise: independent Gaussian noise
// of standard deviation 0.2 around 0.5 per pixel and channel.
struct NoisyFlatImage {
  Image colour = filled(32, 32, 0, 0, 0);
  Image albedo = filled(32, 32, 0.5f, 0.5f, 0.5f);
  Image normal = filled(32, 32, 0, 0, 1);
  NoisyFlatImage() {
    std::mt19937 rng(7);
    std::normal_distribution<float> noise(0.5f, 0.2f);
    for (size_t i = 0; i < colour.pixels.size(); ++i) colour.pixels[i] = i % 4 == 3 ? 1.0f : noise(rng);
  }
};

TEST(Denoiser, RemovesMostOfTheNoiseOfAFlatImage) {
  if (skip_without_library()) GTEST_SKIP() << "Open Image Denoise is not available: " << *denoising_unavailable();
  const NoisyFlatImage in;
  for (const DenoiseQuality quality : {DenoiseQuality::fast, DenoiseQuality::high}) {
    Denoiser denoiser(quality);
    EXPECT_FALSE(denoiser.device_name().empty());
    for (const bool with_aux : {false, true}) {
      const Image out = with_aux ? denoiser.denoise(in.colour, &in.albedo, &in.normal) : denoiser.denoise(in.colour);
      ASSERT_EQ(out.width, 32);
      ASSERT_EQ(out.height, 32);
      for (size_t i = 0; i < out.pixels.size(); ++i) {
        ASSERT_TRUE(std::isfinite(out.pixels[i])) << i;
        if (i % 4 == 3) {
          ASSERT_EQ(out.pixels[i], 1.0f) << "alpha is the input's";
        }
      }
      // The noise's squared error is 0.04 per value; a denoiser that works takes most of it
      // away (a filter that did nothing would keep all of it).
      const double before = squared_error(in.colour, 0.5f), after = squared_error(out, 0.5f);
      EXPECT_LT(after, 0.25 * before) << "aux " << with_aux;
    }
  }
}

TEST(Denoiser, RefusesMismatchedAuxiliaryImages) {
  if (skip_without_library()) GTEST_SKIP() << "Open Image Denoise is not available: " << *denoising_unavailable();
  Denoiser denoiser;
  const Image colour = filled(8, 8, 1, 1, 1), small = filled(4, 4, 1, 1, 1);
  EXPECT_THROW(denoiser.denoise(colour, &small), DenoiseError);
  EXPECT_THROW(denoiser.denoise(colour, nullptr, &colour), DenoiseError);
}

TEST(Denoiser, SaysWhyWhenUnavailable) {
  if (!denoising_unavailable()) GTEST_SKIP() << "the library is available: nothing to report";
  EXPECT_THROW(Denoiser(), DenoiseError);
  EXPECT_FALSE(denoising_unavailable()->empty());
}

}  // namespace
}  // namespace glint
