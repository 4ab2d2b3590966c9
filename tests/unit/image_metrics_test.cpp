// Error metrics of an image against a reference (renderer/image_metrics.h): values worked out by
// hand, the identity, a uniform 10% overexposure, trimming, and images that cannot be compared.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/image_metrics.h"

namespace glint {
namespace {

Image constant_image(int w, int h, float r, float g, float b, float a = 1.0f) {
  Image img;
  img.width = w;
  img.height = h;
  for (int i = 0; i < w * h; ++i) img.pixels.insert(img.pixels.end(), {r, g, b, a});
  return img;
}

// A reference with varied values, including black and values above 1.
Image varied_image(int w, int h) {
  Image img = constant_image(w, h, 0, 0, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = img.at(x, y);
      p[0] = 0.05f * x;
      p[1] = 0.3f * y;
      p[2] = (x + y) % 3 == 0 ? 0.0f : 4.0f;
    }
  return img;
}

TEST(ImageMetrics, KnownValuesOfATwoPixelImage) {
  Image ref = constant_image(2, 1, 1, 1, 1);
  ref.at(1, 0)[0] = ref.at(1, 0)[1] = ref.at(1, 0)[2] = 0;
  Image img = ref;
  img.at(0, 0)[0] = 2.0f;  // error 1 on a reference of 1
  img.at(1, 0)[0] = 0.1f;  // error 0.1 on a reference of 0
  ImageMetrics m = compare_images(img, ref);
  // relMSE: (1^2 / (1 + 0.01) + 0.1^2 / (0 + 0.01)) over 6 channel values.
  EXPECT_NEAR(m.relmse, (1.0 / 1.01 + 1.0) / 6.0, 1e-7);
  // Two pixels: 0.1% of 2 rounds down to none trimmed.
  EXPECT_NEAR(m.relmse_trimmed, m.relmse, 1e-12);
  // MAPE: (1 / 1.01 + 0.1 / 0.01) / 6.
  EXPECT_NEAR(m.mape, (1.0 / 1.01 + 10.0) / 6.0, 1e-6);
  // Luminance sums: image 0.2126*2 + 0.7152 + 0.0722 + 0.2126*0.1, reference 1.
  EXPECT_NEAR(m.mean_bias, (0.4252 + 0.7152 + 0.0722 + 0.02126) - 1.0, 1e-6);
}

TEST(ImageMetrics, IdenticalImagesHaveNoError) {
  Image ref = varied_image(17, 9);
  ImageMetrics m = compare_images(ref, ref);
  EXPECT_EQ(m.relmse, 0.0);
  EXPECT_EQ(m.relmse_trimmed, 0.0);
  EXPECT_EQ(m.mape, 0.0);
  EXPECT_EQ(m.mean_bias, 0.0);
}

TEST(ImageMetrics, TenPercentBrighterOnAConstantImage) {
  ImageMetrics m = compare_images(constant_image(8, 8, 1.1f, 1.1f, 1.1f), constant_image(8, 8, 1, 1, 1));
  EXPECT_NEAR(m.mean_bias, 0.1, 1e-6);
  EXPECT_NEAR(m.relmse, 0.01 / 1.01, 1e-7);
  EXPECT_NEAR(m.relmse_trimmed, 0.01 / 1.01, 1e-7);
  EXPECT_NEAR(m.mape, 0.1 / 1.01, 1e-6);
}

TEST(ImageMetrics, TenPercentBrighterOnAVariedImage) {
  Image ref = varied_image(20, 12);
  Image img = ref;
  for (size_t i = 0; i < img.pixels.size(); ++i)
    if (i % 4 != 3) img.pixels[i] *= 1.1f;
  // Every channel value r contributes (0.1 r)^2 / (r^2 + 0.01); the bias is exactly 10%.
  double expected = 0;
  for (size_t i = 0; i < ref.pixels.size(); ++i)
    if (i % 4 != 3) {
      double r = ref.pixels[i];
      expected += 0.01 * r * r / (r * r + 0.01);
    }
  expected /= 3.0 * ref.width * ref.height;
  ImageMetrics m = compare_images(img, ref);
  EXPECT_NEAR(m.mean_bias, 0.1, 1e-6);
  EXPECT_NEAR(m.relmse, expected, 1e-6 * expected);
}

TEST(ImageMetrics, TrimmingRemovesASingleOutlier) {
  // 32x32 = 1024 pixels: 0.1% rounds down to exactly one trimmed pixel.
  Image ref = constant_image(32, 32, 1, 1, 1);
  Image img = constant_image(32, 32, 1.1f, 1.1f, 1.1f);
  float* firefly = img.at(5, 7);
  firefly[0] = firefly[1] = firefly[2] = 100.0f;
  ImageMetrics m = compare_images(img, ref);
  const double small = 0.01 / 1.01, big = 99.0 * 99.0 / 1.01;
  EXPECT_NEAR(m.relmse, (1023 * small + big) / 1024, 1e-4);
  EXPECT_NEAR(m.relmse_trimmed, small, 1e-6);
  EXPECT_GT(m.relmse, 100 * m.relmse_trimmed);
}

TEST(ImageMetrics, FewerThanAThousandPixelsTrimNothing) {
  Image ref = constant_image(37, 27, 1, 1, 1);  // 999 pixels
  Image img = ref;
  img.at(3, 3)[1] = 50.0f;
  ImageMetrics m = compare_images(img, ref);
  EXPECT_GT(m.relmse, 0.0);
  EXPECT_DOUBLE_EQ(m.relmse_trimmed, m.relmse);
}

TEST(ImageMetrics, ABlackReferenceHasNoRelativeBias) {
  ImageMetrics m = compare_images(constant_image(4, 4, 0.5f, 0.5f, 0.5f), constant_image(4, 4, 0, 0, 0));
  EXPECT_TRUE(std::isnan(m.mean_bias));
  EXPECT_NEAR(m.relmse, 0.25 / 0.01, 1e-4);  // epsilon keeps relMSE finite
}

TEST(ImageMetrics, SizeMismatchThrowsWithBothSizes) {
  try {
    compare_images(constant_image(32, 16, 1, 1, 1), constant_image(16, 32, 1, 1, 1));
    FAIL() << "no exception";
  } catch (const ImageMetricsError& e) {
    EXPECT_NE(std::string(e.what()).find("32x16"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("16x32"), std::string::npos) << e.what();
  }
  EXPECT_THROW(compare_images(Image{}, Image{}), ImageMetricsError);
  Image truncated = constant_image(4, 4, 1, 1, 1);
  truncated.pixels.resize(10);
  EXPECT_THROW(compare_images(truncated, constant_image(4, 4, 1, 1, 1)), ImageMetricsError);
}

TEST(ImageMetrics, NonFiniteCountIsTheSumOfAlpha) {
  Image acc = constant_image(3, 2, 0.5f, 0.5f, 0.5f, 0.0f);
  acc.at(0, 0)[3] = 2;
  acc.at(2, 1)[3] = 5;
  EXPECT_EQ(nonfinite_count(acc), 7.0);
}

}  // namespace
}  // namespace glint
