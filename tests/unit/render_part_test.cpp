// Render parts (renderer/render_part.h): sample ranges, the header round trip, the checks that
// refuse a set of parts (gap, overlap, another render) or a part (its header, its pixels) and
// the sample-weighted mean.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "renderer/part_merge.h"
#include "renderer/render_part.h"
#include "tests/part_fixtures.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

PartInfo part(int64_t first, int64_t end) {
  PartInfo p;
  p.digest = 0x1234;
  p.width = 2;
  p.height = 1;
  p.seed = 7;
  p.range = {first, end};
  return p;
}

std::vector<std::filesystem::path> names(size_t n) {
  std::vector<std::filesystem::path> files;
  for (size_t i = 0; i < n; ++i) files.push_back("p" + std::to_string(i) + ".exr");
  return files;
}

std::string joined(const std::vector<std::string>& problems) {
  std::string s;
  for (const std::string& p : problems) s += p + "\n";
  return s;
}

TEST(SampleRange, ParsesAAndB) {
  EXPECT_EQ(parse_sample_range("0:16"), (SampleRange{0, 16}));
  EXPECT_EQ(parse_sample_range("16:17"), (SampleRange{16, 17}));
  EXPECT_EQ(parse_sample_range("0:4294967296"), (SampleRange{0, int64_t(1) << 32}));
  for (const char* bad : {"", "4", "4:4", "5:4", "-1:4", "0:4294967297", "a:b", "1:2:3", " 1:2", "1:2 "})
    EXPECT_FALSE(parse_sample_range(bad)) << bad;
  EXPECT_EQ(format_sample_range({3, 9}), "3:9");
}

TEST(MergeChecks, AcceptsAnExactCoverInAnyOrder) {
  EXPECT_EQ(joined(merge_problems({part(16, 32), part(0, 16), part(32, 40)}, names(3))), "");
  EXPECT_EQ(joined(merge_problems({part(16, 32), part(0, 16)}, names(2), 32)), "");
}

TEST(MergeChecks, NamesAGap) {
  EXPECT_EQ(joined(merge_problems({part(0, 8), part(16, 32)}, names(2))),
            "samples 8:16 are missing (no part has them)\n");
  EXPECT_EQ(joined(merge_problems({part(4, 8)}, names(1))), "samples 0:4 are missing (no part has them)\n");
  // The end is missing only where the total is known.
  EXPECT_EQ(joined(merge_problems({part(0, 8)}, names(1), 12)), "samples 8:12 are missing (no part has them)\n");
}

TEST(MergeChecks, NamesAnOverlapAndItsFiles) {
  EXPECT_EQ(joined(merge_problems({part(0, 16), part(10, 20)}, names(2))),
            "samples 10:16 overlap: in both p0.exr and p1.exr\n");
  EXPECT_EQ(joined(merge_problems({part(0, 16), part(0, 16)}, names(2))),
            "samples 0:16 overlap: in both p0.exr and p1.exr\n");
  EXPECT_EQ(joined(merge_problems({part(0, 20)}, names(1), 16)),
            "p0.exr has samples up to 20, beyond the 16 asked for\n");
}

TEST(MergeChecks, RefusesPartsOfAnotherRender) {
  PartInfo digest = part(8, 16), size = part(8, 16), seed = part(8, 16), sampler = part(8, 16),
           display = part(8, 16);
  digest.digest = 0x99;
  size.width = 3;
  seed.seed = 8;
  sampler.sampler = SamplerKind::pcg;
  display.display.exposure = 1;
  const auto check = [](const PartInfo& other) { return joined(merge_problems({part(0, 8), other}, names(2))); };
  EXPECT_EQ(check(digest), "p1.exr is not part of the render of p0.exr: its digest (scene, assets and estimator "
                           "options) is 0000000000000099, not 0000000000001234\n");
  EXPECT_EQ(check(size), "p1.exr is not part of the render of p0.exr: its size is 3x1, not 2x1\n");
  EXPECT_EQ(check(seed), "p1.exr is not part of the render of p0.exr: its seed is 8, not 7\n");
  EXPECT_EQ(check(sampler), "p1.exr is not part of the render of p0.exr: its sampler is pcg, not sobol\n");
  EXPECT_NE(check(display).find("display settings"), std::string::npos);
}

// Two parts of 4 and 12 samples: each pixel is weighted by its finite samples (alpha: discarded).
TEST(MergeParts, WeighsEachPixelByItsFiniteSamples) {
  RenderPart a{"a.exr", part(0, 4), {2, 1, {1, 2, 3, 0, /**/ 1, 1, 1, 2}}};
  RenderPart b{"b.exr", part(4, 16), {2, 1, {5, 6, 7, 0, /**/ 3, 3, 3, 2}}};
  const Image m = merge_part_images({a, b});
  // Pixel 0: (4*1 + 12*5)/16 = 4; pixel 1: (2*1 + 10*3)/12 = 8/3, 4 discarded.
  EXPECT_EQ(m.pixels[0], 4.0f);
  EXPECT_EQ(m.pixels[1], 5.0f);
  EXPECT_EQ(m.pixels[2], 6.0f);
  EXPECT_EQ(m.pixels[3], 0.0f);
  EXPECT_EQ(m.pixels[4], static_cast<float>(32.0 / 12.0));
  EXPECT_EQ(m.pixels[7], 4.0f);
}

TEST(RenderPartFile, RoundTripsItsHeaderAndDiscardedCounts) {
  test::TempDir dir;
  PartInfo info = part(16, 48);
  info.digest = 0xfedcba9876543210ull;
  info.display = {-1.5f, Tonemap::linear};
  save_part_image(dir / "p.exr", info, {2, 1, {0.25f, 0.5f, 1.5f, 3, /**/ 0, 0, 0, 0}});
  const RenderPart p = load_render_part(dir / "p.exr");
  EXPECT_EQ(p.info.digest, info.digest);
  EXPECT_EQ(p.info.range, info.range);
  EXPECT_EQ(p.info.seed, 7u);
  EXPECT_EQ(p.info.display, info.display);
  EXPECT_EQ(p.image.pixels, (std::vector<float>{0.25f, 0.5f, 1.5f, 3, 0, 0, 0, 0}));
  // Any viewer sees an opaque image: A is 1, the counts are a channel of their own.
  const Image plain = load_image(dir / "p.exr", ColorEncoding::linear);
  EXPECT_EQ(plain.pixels[3], 1.0f);
}

TEST(RenderPartFile, RefusesAnExrWithoutAHeader) {
  test::TempDir dir;
  save_image(dir / "plain.exr", {1, 1, {1, 1, 1, 1}});
  EXPECT_THROW(load_render_part(dir / "plain.exr"), PartError);  // no glint.digest
  try {
    Image one{1, 1, {1, 1, 1, 0}};
    save_exr(dir / "no-header.exr", one, {{"glint.width", "1"}}, "glint.discarded");
    load_render_part(dir / "no-header.exr");
    FAIL() << "no error";
  } catch (const PartError& e) {
    EXPECT_NE(std::string(e.what()).find("no-header.exr: not a glint render part (no glint.digest"), std::string::npos)
        << e.what();
  }
}

// The header alone says whether a file is a part: the data window must be the size the glint
// fields say, and the channels A, B, G, R and glint.discarded in 32-bit float.
TEST(RenderPartFile, RefusesAHeaderThatIsNotAPartsBeforeItsPixels) {
  test::TempDir dir;
  const Image two{2, 1, {0, 0, 0, 0, 0, 0, 0, 0}};
  PartInfo wide = part(0, 4);
  wide.width = 3;
  save_part_image(dir / "window.exr", wide, two);
  PartInfo huge = part(0, 4);
  huge.width = huge.height = 16384;
  save_part_image(dir / "huge.exr", huge, two);
  save_exr(dir / "channels.exr", two, {{"glint.digest", "1234"}, {"glint.width", "2"}, {"glint.height", "1"},
                                       {"glint.seed", "7"}, {"glint.sampler", "sobol"}, {"glint.samples", "0:4"},
                                       {"glint.exposure", "0"}, {"glint.tonemap", "filmic"}});
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"window.exr", "window.exr: its pixels are 2x1 at (0, 0) but its header says 3x1 at (0, 0)"},
      {"huge.exr", "huge.exr: its header says 16384x16384, beyond the renderer's film limits (1 to 16384 pixels a "
                   "side, 67108864 in all)"},
      {"channels.exr", "channels.exr: its channels are A, B, G, R; a part has A, B, G, R and glint.discarded, all "
                       "32-bit float"}};
  for (const auto& [name, message] : cases) {
    for (bool header_only : {true, false}) {
      try {
        if (header_only) read_part_header(dir / name);
        else load_render_part(dir / name);
        ADD_FAILURE() << name << ": no error";
      } catch (const PartError& e) {
        EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
      }
    }
  }
}

// glint farm status reads the header alone: a part whose pixels are cut off still says which
// samples it has (the merge refuses it when it decodes them).
TEST(RenderPartFile, ReadsTheHeaderWithoutThePixels) {
  test::TempDir dir;
  Image image{64, 64, std::vector<float>(64 * 64 * 4)};
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = i % 4 == 3 ? 0.0f : float(i % 97) / 97.0f;
  PartInfo info = part(8, 24);
  info.width = info.height = 64;
  save_part_image(dir / "p.exr", info, image);
  const std::string bytes = test::file_bytes(dir / "p.exr");
  test::write_file_bytes(dir / "p.exr", bytes.substr(0, test::exr_attribute_data(bytes, "") + 8));
  EXPECT_EQ(read_part_header(dir / "p.exr"), info);
  EXPECT_THROW(load_render_part(dir / "p.exr"), ImageError);
}

// Values that no mean of samples has are refused, naming the file, the pixel and the channel.
TEST(RenderPartFile, RefusesImpossiblePixels) {
  test::TempDir dir;
  const float nan = std::nanf(""), inf = INFINITY;
  struct Case {
    int channel;
    float value;
    const char* message;
  };
  const std::vector<Case> cases = {
      {0, nan, "pixel (2, 1) channel R is nan (radiance must be finite and not negative)"},
      {1, inf, "pixel (2, 1) channel G is inf (radiance"},
      {2, -0.5f, "pixel (2, 1) channel B is -0.5 (radiance"},
      {3, -1, "pixel (2, 1) channel glint.discarded is -1 (a count of discarded samples: an integer from 0 to the "
              "part's 16 samples)"},
      {3, nan, "pixel (2, 1) channel glint.discarded is nan"},
      {3, 2.5f, "pixel (2, 1) channel glint.discarded is 2.5"},
      {3, 17, "pixel (2, 1) channel glint.discarded is 17"},
  };
  for (const Case& c : cases) {
    Image image{3, 2, std::vector<float>(3 * 2 * 4, 0.25f)};
    for (size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 16;  // every sample discarded: allowed
    image.at(2, 1)[c.channel] = c.value;
    PartInfo info = part(0, 16);
    info.width = 3;
    info.height = 2;
    save_part_image(dir / "p.exr", info, image);
    try {
      load_render_part(dir / "p.exr");
      ADD_FAILURE() << c.message << ": no error";
    } catch (const PartError& e) {
      EXPECT_NE(std::string(e.what()).find("p.exr: " + std::string(c.message)), std::string::npos) << e.what();
    }
    RenderPart in_memory{"memory.exr", info, image};
    EXPECT_THROW(merge_part_images({in_memory}), PartError) << c.message;
  }
}

}  // namespace
}  // namespace glint
