// Image reading/writing (renderer/image.h) and the procedural assets (procedural_assets.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <stb_image_write.h>

#include "renderer/image.h"
#include "renderer/procedural_assets.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

using test::TempDir;

// A deterministic test pattern with distinct values in every channel.
Image pattern(int width, int height, float scale, bool with_alpha) {
  Image image;
  image.width = width;
  image.height = height;
  image.pixels.resize(static_cast<size_t>(width) * height * 4);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float* p = image.at(x, y);
      p[0] = scale * static_cast<float>(x) / (width - 1);
      p[1] = scale * static_cast<float>(y) / (height - 1);
      p[2] = scale * static_cast<float>((x * 7 + y * 13) % 31) / 30.0f;
      p[3] = with_alpha ? static_cast<float>((x + y) % 5) / 4.0f : 1.0f;
    }
  return image;
}

std::vector<char> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void cut_in_half(const fs::path& path) {
  const std::vector<char> bytes = read_bytes(path);
  write_bytes(path, std::string(bytes.begin(), bytes.begin() + bytes.size() / 2));
}

// --- a minimal PNG writer (stb cannot write 16-bit PNG): stored, uncompressed deflate blocks ---

uint32_t crc32(const std::string& data) {
  uint32_t crc = 0xffffffffu;
  for (unsigned char byte : data) {
    crc ^= byte;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void put_be32(std::string& s, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) s += static_cast<char>((v >> shift) & 0xff);
}

std::string png_chunk(const std::string& type, const std::string& data) {
  std::string chunk;
  put_be32(chunk, static_cast<uint32_t>(data.size()));
  chunk += type + data;
  put_be32(chunk, crc32(type + data));
  return chunk;
}

// `samples` holds width * height * channels values of `bit_depth` (8 or 16) bits.
std::string make_png(int width, int height, int channels, int bit_depth,
                     const std::vector<uint16_t>& samples) {
  const char color_type[] = {0, 0, 4, 2, 6};  // by channel count: grey, grey+alpha, RGB, RGBA
  std::string ihdr;
  put_be32(ihdr, width);
  put_be32(ihdr, height);
  ihdr += {static_cast<char>(bit_depth), color_type[channels], 0, 0, 0};
  std::string raw;  // filter byte 0 (none) before every row, samples big-endian
  for (int y = 0; y < height; ++y) {
    raw += '\0';
    for (int i = 0; i < width * channels; ++i) {
      const uint16_t v = samples[static_cast<size_t>(y) * width * channels + i];
      if (bit_depth == 16) raw += static_cast<char>(v >> 8);
      raw += static_cast<char>(v & 0xff);
    }
  }
  std::string zlib = "\x78\x01";
  for (size_t pos = 0; pos == 0 || pos < raw.size(); pos += 65535) {
    const size_t n = std::min<size_t>(65535, raw.size() - pos);
    zlib += static_cast<char>(pos + n >= raw.size() ? 1 : 0);  // BFINAL, BTYPE 00 (stored)
    zlib += {static_cast<char>(n & 0xff), static_cast<char>(n >> 8),
             static_cast<char>(~n & 0xff), static_cast<char>((~n >> 8) & 0xff)};
    zlib += raw.substr(pos, n);
  }
  uint32_t a = 1, b = 0;  // Adler-32 of the uncompressed data
  for (unsigned char c : raw) a = (a + c) % 65521, b = (b + a) % 65521;
  put_be32(zlib, (b << 16) | a);
  return std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", ihdr) + png_chunk("IDAT", zlib) +
         png_chunk("IEND", "");
}

void expect_image_error_naming(const fs::path& path, ColorEncoding encoding = ColorEncoding::srgb) {
  try {
    load_image(path, encoding);
    ADD_FAILURE() << "load_image accepted " << path;
  } catch (const ImageError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string() + ": "), std::string::npos) << e.what();
  }
}

void expect_probe_error_naming(const fs::path& path) {
  try {
    probe_image(path);
    ADD_FAILURE() << "probe_image accepted " << path;
  } catch (const ImageError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string() + ": "), std::string::npos) << e.what();
  }
}

}  // namespace

// --- transfer functions ---------------------------------------------------------------------------

TEST(ImageIo, SrgbTransferFunctionMatchesKnownValues) {
  EXPECT_EQ(srgb_to_linear(0.0f), 0.0f);
  EXPECT_NEAR(srgb_to_linear(1.0f), 1.0f, 1e-6);
  EXPECT_NEAR(srgb_to_linear(188.0f / 255), 0.5029f, 1e-4);  // not 2.2 gamma (that gives 0.5111)
  EXPECT_NEAR(srgb_to_linear(0.04045f), 0.04045f / 12.92f, 1e-7);
  for (int i = 0; i <= 255; ++i) {
    const float c = i / 255.0f;
    EXPECT_NEAR(linear_to_srgb(srgb_to_linear(c)), c, 1e-5) << i;
  }
}

TEST(ImageIo, EightBitPngIsSrgbDecodedExceptAlpha) {
  TempDir dir;
  const unsigned char rgba[] = {0, 255, 188, 188, 188, 0, 255, 64};
  ASSERT_TRUE(stbi_write_png((dir / "a.png").string().c_str(), 2, 1, 4, rgba, 8));
  const Image srgb = load_image(dir / "a.png", ColorEncoding::srgb);
  ASSERT_EQ(srgb.width, 2);
  ASSERT_EQ(srgb.height, 1);
  EXPECT_EQ(srgb.at(0, 0)[0], 0.0f);
  EXPECT_NEAR(srgb.at(0, 0)[1], 1.0f, 1e-6);
  EXPECT_NEAR(srgb.at(0, 0)[2], 0.5029f, 1e-4);
  EXPECT_NEAR(srgb.at(0, 0)[3], 188.0f / 255, 1e-6);  // alpha is linear
  EXPECT_NEAR(srgb.at(1, 0)[3], 64.0f / 255, 1e-6);
  const Image linear = load_image(dir / "a.png", ColorEncoding::linear);
  EXPECT_NEAR(linear.at(0, 0)[2], 188.0f / 255, 1e-6);
}

// --- round trips ----------------------------------------------------------------------------------

TEST(ImageIo, PngRoundTripWithinQuantisation) {
  TempDir dir;
  for (bool alpha : {false, true}) {
    const Image original = pattern(37, 23, 1.0f, alpha);
    save_image(dir / "rt.png", original);
    const ImageInfo info = probe_image(dir / "rt.png");
    EXPECT_EQ(info.width, 37);
    EXPECT_EQ(info.height, 23);
    EXPECT_EQ(info.channels, alpha ? 4 : 3);
    EXPECT_FALSE(info.high_dynamic_range);
    const Image loaded = load_image(dir / "rt.png", ColorEncoding::linear);
    ASSERT_EQ(loaded.pixels.size(), original.pixels.size());
    for (size_t i = 0; i < original.pixels.size(); ++i)
      ASSERT_NEAR(loaded.pixels[i], original.pixels[i], 0.5f / 255 + 1e-6f) << i;
  }
  // Nothing but the file itself is left behind (the temporary was renamed).
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
}

TEST(ImageIo, PngClampsOutOfRangeValues) {
  TempDir dir;
  Image image = pattern(2, 2, 1.0f, false);
  image.at(0, 0)[0] = -3.0f;
  image.at(0, 0)[1] = 7.0f;
  image.at(0, 0)[2] = std::nanf("");
  save_image(dir / "c.png", image);
  const Image loaded = load_image(dir / "c.png", ColorEncoding::linear);
  EXPECT_EQ(loaded.at(0, 0)[0], 0.0f);
  EXPECT_EQ(loaded.at(0, 0)[1], 1.0f);
  EXPECT_EQ(loaded.at(0, 0)[2], 0.0f);
}

TEST(ImageIo, HdrRoundTripWithinRgbePrecision) {
  TempDir dir;
  Image original = pattern(64, 16, 1.0f, true);
  // Spread the values over seven decades, as an environment map would.
  for (size_t i = 0; i < original.pixels.size(); i += 4)
    for (int c = 0; c < 3; ++c)
      original.pixels[i + c] = 1e-3f * std::pow(1e7f, original.pixels[i + c]) * (c + 1) / 3;
  save_image(dir / "rt.hdr", original);
  const ImageInfo info = probe_image(dir / "rt.hdr");
  EXPECT_EQ(info.width, 64);
  EXPECT_TRUE(info.high_dynamic_range);
  const Image loaded = load_image(dir / "rt.hdr", ColorEncoding::srgb);  // encoding is ignored
  ASSERT_EQ(loaded.pixels.size(), original.pixels.size());
  for (size_t i = 0; i < original.pixels.size(); i += 4) {
    // RGBE shares one exponent per pixel: the error is relative to the largest channel.
    const float largest = std::max({original.pixels[i], original.pixels[i + 1], original.pixels[i + 2]});
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(loaded.pixels[i + c], original.pixels[i + c], 0.01f * largest) << i;
    ASSERT_EQ(loaded.pixels[i + 3], 1.0f);  // .hdr has no alpha
  }
}

TEST(ImageIo, ExrRoundTripIsExact) {
  TempDir dir;
  Image original = pattern(19, 11, 1.0f, true);
  original.at(0, 0)[0] = -2.5f;
  original.at(1, 0)[1] = 65504.0f * 100;  // beyond half-float range: float32 keeps it
  original.at(2, 0)[2] = 1e-9f;
  save_image(dir / "rt.exr", original);
  const ImageInfo info = probe_image(dir / "rt.exr");
  EXPECT_EQ(info.width, 19);
  EXPECT_EQ(info.height, 11);
  EXPECT_EQ(info.channels, 4);
  EXPECT_TRUE(info.high_dynamic_range);
  const Image loaded = load_image(dir / "rt.exr", ColorEncoding::srgb);
  ASSERT_EQ(loaded.width, 19);
  ASSERT_EQ(loaded.height, 11);
  EXPECT_EQ(loaded.pixels, original.pixels);
}

TEST(ImageIo, SixteenBitPngIsLinear) {
  TempDir dir;
  const std::vector<uint16_t> samples = {0, 65535, 32768, 1000,  //
                                         12345, 54321, 1, 65534};
  write_bytes(dir / "16.png", make_png(2, 1, 4, 16, samples));
  const ImageInfo info = probe_image(dir / "16.png");
  EXPECT_EQ(info.channels, 4);
  EXPECT_TRUE(info.high_dynamic_range);
  const Image image = load_image(dir / "16.png", ColorEncoding::srgb);  // no sRGB decode
  ASSERT_EQ(image.pixels.size(), 8u);
  for (size_t i = 0; i < samples.size(); ++i)
    EXPECT_FLOAT_EQ(image.pixels[i], samples[i] / 65535.0f) << i;

  write_bytes(dir / "16g.png", make_png(1, 1, 1, 16, {40000}));
  const Image grey = load_image(dir / "16g.png", ColorEncoding::srgb);
  EXPECT_FLOAT_EQ(grey.pixels[0], 40000 / 65535.0f);
  EXPECT_FLOAT_EQ(grey.pixels[2], 40000 / 65535.0f);
  EXPECT_EQ(grey.pixels[3], 1.0f);
}

TEST(ImageIo, GreyAndGreyAlphaExpandToRgba) {
  TempDir dir;
  const unsigned char grey[] = {188, 0};
  const unsigned char grey_alpha[] = {188, 128, 255, 0};
  ASSERT_TRUE(stbi_write_png((dir / "g.png").string().c_str(), 2, 1, 1, grey, 2));
  ASSERT_TRUE(stbi_write_png((dir / "ga.png").string().c_str(), 2, 1, 2, grey_alpha, 4));
  EXPECT_EQ(probe_image(dir / "g.png").channels, 1);
  EXPECT_EQ(probe_image(dir / "ga.png").channels, 2);

  const Image g = load_image(dir / "g.png", ColorEncoding::srgb);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(g.at(0, 0)[c], 0.5029f, 1e-4);
  EXPECT_EQ(g.at(0, 0)[3], 1.0f);
  EXPECT_EQ(g.at(1, 0)[0], 0.0f);

  const Image ga = load_image(dir / "ga.png", ColorEncoding::linear);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(ga.at(0, 0)[c], 188.0f / 255, 1e-6);
  EXPECT_NEAR(ga.at(0, 0)[3], 128.0f / 255, 1e-6);
  EXPECT_EQ(ga.at(1, 0)[0], 1.0f);
  EXPECT_EQ(ga.at(1, 0)[3], 0.0f);
}

// --- bad files ------------------------------------------------------------------------------------

TEST(ImageIo, TruncatedFilesAreRejected) {
  TempDir dir;
  const Image image = pattern(64, 48, 3.0f, true);
  save_image(dir / "t.png", pattern(64, 48, 1.0f, true));
  save_image(dir / "t.hdr", image);                   // run-length encoded scanlines
  save_image(dir / "narrow.hdr", pattern(4, 64, 3.0f, false));  // flat scanlines (width < 8)
  save_image(dir / "t.exr", image);
  std::vector<unsigned char> jpg_pixels(64 * 48 * 3, 90);
  ASSERT_TRUE(stbi_write_jpg((dir / "t.jpg").string().c_str(), 64, 48, 3, jpg_pixels.data(), 90));
  for (const char* name : {"t.png", "t.hdr", "narrow.hdr", "t.exr", "t.jpg"}) {
    SCOPED_TRACE(name);
    EXPECT_NO_THROW(load_image(dir / name, ColorEncoding::srgb));
    cut_in_half(dir / name);
    expect_image_error_naming(dir / name);
  }
  // With the header itself cut, probing fails too.
  save_image(dir / "h.png", image);
  write_bytes(dir / "h.png", std::string(read_bytes(dir / "h.png").data(), 12));
  expect_probe_error_naming(dir / "h.png");
  save_image(dir / "h.exr", image);
  write_bytes(dir / "h.exr", std::string(read_bytes(dir / "h.exr").data(), 40));
  expect_probe_error_naming(dir / "h.exr");
  expect_image_error_naming(dir / "h.exr");
}

TEST(ImageIo, EveryPrefixOfASmallFileIsRejected) {
  // Cut anywhere, including inside headers and run-length codes: an error, never a crash, a
  // hang (stb's .hdr decoder loops forever on zeros past the end) or garbage pixels.
  TempDir dir;
  save_image(dir / "s.png", pattern(8, 8, 1.0f, true));
  save_image(dir / "rle.hdr", pattern(16, 3, 5.0f, false));
  save_image(dir / "flat.hdr", pattern(3, 3, 5.0f, false));
  save_image(dir / "s.exr", pattern(4, 4, 5.0f, true));
  for (const char* name : {"s.png", "rle.hdr", "flat.hdr", "s.exr"}) {
    const std::vector<char> bytes = read_bytes(dir / name);
    const fs::path cut = dir / (std::string("cut-") + name);
    for (size_t length = 0; length < bytes.size(); ++length) {
      write_bytes(cut, std::string(bytes.data(), length));
      EXPECT_THROW(load_image(cut, ColorEncoding::srgb), ImageError) << name << " cut at " << length;
    }
  }
}

TEST(ImageIo, NonImageMissingAndEmptyFilesAreRejected) {
  TempDir dir;
  write_bytes(dir / "notes.png", "this is not an image, whatever its name says\n");
  write_bytes(dir / "empty.hdr", "");
  for (const char* name : {"notes.png", "empty.hdr", "missing.exr"}) {
    SCOPED_TRACE(name);
    expect_probe_error_naming(dir / name);
    expect_image_error_naming(dir / name);
  }
  expect_probe_error_naming(dir.path());  // a folder
}

TEST(ImageIo, HugeDimensionsAreRefused) {
  TempDir dir;
  // A valid 20000 x 1 grey PNG: small on disk, but over the 16384 limit.
  write_bytes(dir / "wide.png", make_png(20000, 1, 1, 8, std::vector<uint16_t>(20000, 7)));
  expect_probe_error_naming(dir / "wide.png");
  expect_image_error_naming(dir / "wide.png");
  // A header that claims 1e9 x 1e9 pixels with no data behind it.
  std::string ihdr;
  put_be32(ihdr, 1000000000);
  put_be32(ihdr, 1000000000);
  ihdr += {8, 0, 0, 0, 0};
  write_bytes(dir / "claim.png", std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", ihdr));
  expect_probe_error_naming(dir / "claim.png");
  expect_image_error_naming(dir / "claim.png");
}

TEST(ImageIo, SaveRejectsUnknownExtensionsAndBadImages) {
  TempDir dir;
  EXPECT_THROW(save_image(dir / "x.bmp", pattern(2, 2, 1, false)), ImageError);
  Image bad = pattern(2, 2, 1, false);
  bad.pixels.pop_back();
  EXPECT_THROW(save_image(dir / "x.png", bad), ImageError);
  EXPECT_THROW(save_image(dir / "x.exr", Image{}), ImageError);
  EXPECT_THROW(save_image(dir / "no-such-folder" / "x.png", pattern(2, 2, 1, false)), ImageError);
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

// --- procedural assets ----------------------------------------------------------------------------

TEST(Procedural, GeneratorsAreDeterministicAndInRange) {
  using Generator = Image (*)(int);
  const Generator generators[] = {procedural::wood_color,    procedural::wood_roughness,
                                  procedural::leather_color, procedural::leather_roughness,
                                  procedural::metal_color,   procedural::metal_roughness,
                                  procedural::checker_with_holes};
  for (Generator generate : generators) {
    const Image a = generate(256), b = generate(256);
    ASSERT_EQ(a.width, 256);
    ASSERT_EQ(a.height, 256);
    ASSERT_EQ(a.pixels.size(), 256u * 256 * 4);
    EXPECT_EQ(a.pixels, b.pixels);
    float lo = 1, hi = 0;
    for (float v : a.pixels) lo = std::min(lo, v), hi = std::max(hi, v);
    EXPECT_GE(lo, 0.0f);
    EXPECT_LE(hi, 1.0f);
  }
  EXPECT_EQ(procedural::sky().pixels, procedural::sky().pixels);
}

TEST(Procedural, TexturesTileSeamlessly) {
  // The jump across the wrap-around seam is no larger than typical neighbour differences.
  for (const Image& image : {procedural::wood_color(), procedural::leather_color(),
                             procedural::metal_color()}) {
    auto column_step = [&](int x0, int x1) {
      double sum = 0;
      for (int y = 0; y < image.height; ++y)
        for (int c = 0; c < 3; ++c) sum += std::abs(image.at(x0, y)[c] - image.at(x1, y)[c]);
      return sum;
    };
    double typical = 0;
    for (int x = 0; x + 1 < image.width; ++x) typical += column_step(x, x + 1);
    typical /= image.width - 1;
    EXPECT_LT(column_step(image.width - 1, 0), 3 * typical);
  }
}

TEST(Procedural, CheckerHasRoundHoles) {
  const Image checker = procedural::checker_with_holes(256);
  EXPECT_EQ(checker.at(16, 16)[3], 0.0f);  // centre of the first cell
  EXPECT_EQ(checker.at(0, 0)[3], 1.0f);    // cell corner
  EXPECT_EQ(checker.at(30, 16)[3], 1.0f);  // beside the hole
  double open = 0;  // the anti-aliased alpha approximates each pixel's coverage
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) open += 1 - checker.at(x, y)[3];
  // A hole of radius 0.3 cells leaves pi * 0.3^2 of its cell open (to 1%).
  EXPECT_NEAR(open / (256.0 * 256.0), 3.14159265 * 0.09, 0.01 * 3.14159265 * 0.09);
  // Neighbouring cells differ in colour.
  EXPECT_NE(checker.at(0, 0)[1], checker.at(32, 0)[1]);
}

TEST(Procedural, LatLongMappingFollowsTheDesign) {
  const glm::vec3 up = procedural::latlong_direction(0.3f, 0.0f);
  EXPECT_NEAR(up.y, 1.0f, 1e-6);
  const glm::vec3 x = procedural::latlong_direction(0.0f, 0.5f);
  EXPECT_NEAR(x.x, 1.0f, 1e-6);
  const glm::vec3 z = procedural::latlong_direction(0.25f, 0.5f);
  EXPECT_NEAR(z.z, 1.0f, 1e-6);
  for (float u : {0.05f, 0.3f, 0.7f, 0.95f})
    for (float v : {0.1f, 0.5f, 0.8f}) {
      const glm::vec2 uv = procedural::latlong_uv(procedural::latlong_direction(u, v));
      EXPECT_NEAR(uv.x, u, 1e-5);
      EXPECT_NEAR(uv.y, v, 1e-5);
    }
}

TEST(Procedural, SkySunIsTheBrightestRegionAndEverythingIsFinite) {
  const procedural::SkyOptions options;
  const Image sky = procedural::sky(options);
  ASSERT_EQ(sky.width, 512);
  ASSERT_EQ(sky.height, 256);
  auto luminance = [](const float* p) { return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2]; };
  int best_x = 0, best_y = 0;
  std::vector<float> sky_values;
  for (int y = 0; y < sky.height; ++y)
    for (int x = 0; x < sky.width; ++x) {
      const float* p = sky.at(x, y);
      for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(p[c]) && p[c] >= 0) << x << "," << y;
      if (luminance(p) > luminance(sky.at(best_x, best_y))) best_x = x, best_y = y;
      if (y < sky.height / 2) sky_values.push_back(luminance(p));
    }
  // The brightest pixel lies on the sun's disc (within a pixel's angular size of it).
  const glm::vec3 sun = procedural::sun_direction(options);
  const glm::vec3 brightest = procedural::latlong_direction((best_x + 0.5f) / sky.width,
                                                            (best_y + 0.5f) / sky.height);
  const float pixel_deg = 360.0f / sky.width;
  EXPECT_LT(glm::degrees(std::acos(std::min(glm::dot(brightest, sun), 1.0f))),
            0.5f * options.sun_diameter_deg + pixel_deg);
  // The sun outshines the typical sky by more than two orders of magnitude (and not by more
  // than 3e4); the sky is brighter than the ground and the first row (straight up) is blue.
  std::nth_element(sky_values.begin(), sky_values.begin() + sky_values.size() / 2, sky_values.end());
  const float median_sky = sky_values[sky_values.size() / 2];
  const float peak = luminance(sky.at(best_x, best_y));
  EXPECT_GT(peak / median_sky, 1e2f);
  EXPECT_LT(peak / median_sky, 3e4f);
  EXPECT_GT(median_sky, luminance(sky.at(0, sky.height - 1)));
  EXPECT_GT(sky.at(100, 0)[2], sky.at(100, 0)[0]);
}

}  // namespace glint
