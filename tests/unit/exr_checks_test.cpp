// The checks made before tinyexr decodes an OpenEXR file (renderer/exr_checks.h): valid PIZ
// files still load, and each malformed part of a PIZ block is refused with what is wrong.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <tinyexr.h>

#include "renderer/exr_checks.h"
#include "renderer/image.h"

namespace glint {
namespace {

// The pattern of piz_file: few distinct values, so that every block compresses (tinyexr stores
// a block raw when compression does not make it shorter).
float pattern_value(int x, int y, int c) { return 0.25f * float(c + 1) + 0.125f * float((x / 8 + y / 8) % 4); }

// A PIZ-compressed scanline file written by tinyexr: RGB, half or float, of pattern_value.
std::vector<unsigned char> piz_file(int width, int height, int pixel_type) {
  std::vector<float> channels[3];
  for (int c = 0; c < 3; ++c)
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        channels[c].push_back(pattern_value(x, y, c));
  EXRHeader header;
  InitEXRHeader(&header);
  EXRImage image;
  InitEXRImage(&image);
  float* planes[3] = {channels[2].data(), channels[1].data(), channels[0].data()};  // B, G, R
  image.images = reinterpret_cast<unsigned char**>(planes);
  image.num_channels = 3;
  image.width = width;
  image.height = height;
  header.num_channels = 3;
  std::vector<EXRChannelInfo> info(3);
  const char* names[3] = {"B", "G", "R"};
  for (int c = 0; c < 3; ++c) std::strncpy(info[c].name, names[c], 255);
  header.channels = info.data();
  std::vector<int> input(3, TINYEXR_PIXELTYPE_FLOAT), stored(3, pixel_type);
  header.pixel_types = input.data();
  header.requested_pixel_types = stored.data();
  header.compression_type = TINYEXR_COMPRESSIONTYPE_PIZ;
  unsigned char* memory = nullptr;
  const char* err = nullptr;
  const size_t size = SaveEXRImageToMemory(&image, &header, &memory, &err);
  if (size == 0) {
    std::string message = err ? err : "?";
    FreeEXRErrorMessage(err);
    throw std::runtime_error("tinyexr cannot write PIZ: " + message);
  }
  std::vector<unsigned char> bytes(memory, memory + size);
  std::free(memory);
  return bytes;
}

// The layout exr_io.cpp derives from the header, for a file of piz_file.
ExrScanlineLayout layout_of(const std::vector<unsigned char>& bytes, int width, int height, int bytes_per_pixel) {
  EXRVersion version;
  EXRHeader header;
  InitEXRHeader(&header);
  const char* err = nullptr;
  if (ParseEXRVersionFromMemory(&version, bytes.data(), bytes.size()) != TINYEXR_SUCCESS ||
      ParseEXRHeaderFromMemory(&header, &version, bytes.data(), bytes.size(), &err) != TINYEXR_SUCCESS)
    throw std::runtime_error("cannot parse the test file");
  ExrScanlineLayout layout;
  layout.table_start = 8 + header.header_len;
  layout.blocks = (height + 31) / 32;
  layout.width = width;
  layout.height = height;
  layout.bytes_per_pixel = bytes_per_pixel;
  FreeEXRHeader(&header);
  return layout;
}

uint64_t offset_of(const std::vector<unsigned char>& b, const ExrScanlineLayout& layout, int block) {
  uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = v << 8 | b[layout.table_start + 8 * size_t(block) + size_t(i)];
  return v;
}
uint32_t get_u32(const std::vector<unsigned char>& b, size_t at) {
  return uint32_t(b[at]) | uint32_t(b[at + 1]) << 8 | uint32_t(b[at + 2]) << 16 | uint32_t(b[at + 3]) << 24;
}
void put_u32(std::vector<unsigned char>& b, size_t at, uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + size_t(i)] = static_cast<unsigned char>(v >> (8 * i));
}
void put_u16(std::vector<unsigned char>& b, size_t at, uint16_t v) {
  b[at] = static_cast<unsigned char>(v);
  b[at + 1] = static_cast<unsigned char>(v >> 8);
}

// The message with which load_image_data refuses `bytes`, or "loaded".
std::string load_error(const std::vector<unsigned char>& bytes, const std::string& label) {
  try {
    load_image_data(bytes, label, ColorEncoding::linear);
  } catch (const ImageError& e) {
    return e.what();
  }
  return "loaded";
}

TEST(ExrChecks, PizFilesStillLoad) {
  for (int type : {TINYEXR_PIXELTYPE_HALF, TINYEXR_PIXELTYPE_FLOAT}) {
    const int width = 37, height = 70;  // three blocks of 32 lines, the last of 6
    const std::vector<unsigned char> bytes = piz_file(width, height, type);
    const ExrScanlineLayout layout = layout_of(bytes, width, height, type == TINYEXR_PIXELTYPE_HALF ? 6 : 12);
    EXPECT_EQ(unsafe_piz_blocks(bytes, layout), "");
    // Every block is compressed (shorter than its raw pixels), so the PIZ parts were checked.
    for (int block = 0; block < layout.blocks; ++block) {
      const uint32_t size = get_u32(bytes, size_t(offset_of(bytes, layout, block)) + 4);
      const int lines = std::min(32, height - 32 * block);
      EXPECT_LT(size, uint32_t(width * lines * layout.bytes_per_pixel)) << block;
    }
    const Image image = load_image_data(bytes, "piz.exr", ColorEncoding::linear);
    ASSERT_EQ(image.width, width);
    ASSERT_EQ(image.height, height);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        for (int c = 0; c < 3; ++c) {
          ASSERT_EQ(image.at(x, y)[c], pattern_value(x, y, c)) << x << "," << y << "," << c;  // exact in half
        }
  }
}

TEST(ExrChecks, MalformedPizBlocksAreNamed) {
  const int width = 37, height = 70;
  const std::vector<unsigned char> good = piz_file(width, height, TINYEXR_PIXELTYPE_HALF);
  const ExrScanlineLayout layout = layout_of(good, width, height, 6);
  const size_t block1 = size_t(offset_of(good, layout, 1));
  const uint32_t size1 = get_u32(good, block1 + 4);
  const size_t data1 = block1 + 8;
  auto damaged = [&](auto change) {
    std::vector<unsigned char> b = good;
    change(b);
    return unsafe_piz_blocks(b, layout);
  };
  const std::string size_text = std::to_string(size1);
  // The bitmap range 0..8000 runs past the block (tinyexr copied it from beyond the block).
  EXPECT_EQ(damaged([&](auto& b) { put_u16(b, data1, 0); put_u16(b, data1 + 2, 8000); }),
            "PIZ block 1 is " + size_text + " bytes, its bitmap needs 8009");
  // An empty bitmap range; the Huffman length is then read at byte 4.
  EXPECT_EQ(damaged([&](auto& b) { put_u16(b, data1, 9); put_u16(b, data1 + 2, 3); put_u32(b, data1 + 4, 5); }),
            "PIZ block 1 has Huffman data of 5 bytes, shorter than its header");
  EXPECT_EQ(damaged([&](auto& b) { put_u16(b, data1, 9); put_u16(b, data1 + 2, 3); put_u32(b, data1 + 4, 0x7fffffff); }),
            "PIZ block 1 has Huffman data of 2147483647 bytes in " + size_text);
  EXPECT_EQ(damaged([&](auto& b) { put_u16(b, data1, 9); put_u16(b, data1 + 2, 3); put_u32(b, data1 + 4, 0xffffffff); }),
            "PIZ block 1 has Huffman data of -1 bytes in " + size_text);
  // A block of 3 bytes: not even the bitmap range fits.
  EXPECT_EQ(damaged([&](auto& b) { put_u32(b, block1 + 4, 3); }), "PIZ block 1 is 3 bytes");
  // Block headers: a size past the file's end, a line outside the data window, an offset into
  // the offset table or past the end.
  EXPECT_EQ(damaged([&](auto& b) { put_u32(b, block1 + 4, 1u << 30); }),
            "PIZ block 1 is 1073741824 bytes, past the end of the file");
  EXPECT_EQ(damaged([&](auto& b) { put_u32(b, block1, 70); }), "PIZ block 1 starts on line 70 of 70");
  EXPECT_EQ(damaged([&](auto& b) { b[layout.table_start + 8] = 0; b[layout.table_start + 9] = 0; }),
            "PIZ block 1 is not inside the file (offset 0)");
  EXPECT_EQ(damaged([&](auto& b) { b[layout.table_start + 8 + 7] = 0x7f; }).rfind("PIZ block 1 is not inside the file", 0), 0u);
  // A block as long as its raw pixels is stored uncompressed: its bytes are not PIZ parts.
  EXPECT_EQ(damaged([&](auto& b) {
              b.resize(b.size() + size_t(37 * 32 * 6));
              put_u32(b, block1 + 4, uint32_t(37 * 32 * 6));
              put_u16(b, data1, 0);
              put_u16(b, data1 + 2, 8000);
            }),
            "");
  // load_image_data names the file and the problem.
  std::vector<unsigned char> bad = good;
  put_u16(bad, data1, 0);
  put_u16(bad, data1 + 2, 8000);
  EXPECT_EQ(load_error(bad, "bad.exr"),
            "bad.exr: corrupt OpenEXR data (PIZ block 1 is " + size_text + " bytes, its bitmap needs 8009)");
}

TEST(ExrChecks, OffsetTablesThatCannotFitAreRefused) {
  EXPECT_EQ(unsafe_offset_table(1000, 200, 100), "");  // 800 bytes for 100 entries: fits
  EXPECT_EQ(unsafe_offset_table(1000, 200, 101), "an offset table of 101 entries does not fit in the file's 1000 bytes");
  EXPECT_EQ(unsafe_offset_table(100, 200, 1), "an offset table of 1 entries does not fit in the file's 100 bytes");
  EXPECT_EQ(level0_tiles(16384, 16384, 1, 1), 1ull << 28);
  EXPECT_EQ(level0_tiles(37, 70, 16, 32), 3ull * 3);
  EXPECT_EQ(level0_tiles(37, 70, 0, 32), 0ull);

  // A chunkCount attribute of 2^31 - 1 in a small scanline file (tinyexr would allocate 16 GiB
  // for its table before reading it).
  std::vector<unsigned char> bytes = piz_file(16, 16, TINYEXR_PIXELTYPE_HALF);
  const std::string count("chunkCount\0int\0\x04\0\0\0\xff\xff\xff\x7f", 23);
  bytes.insert(bytes.begin() + 8, count.begin(), count.end());
  EXPECT_EQ(load_error(bytes, "count.exr"), "count.exr: bad OpenEXR header (an offset table of 2147483647 entries "
                                            "does not fit in the file's " + std::to_string(bytes.size()) + " bytes)");
}

// Tiled PIZ files are refused outright (their blocks are not checked).
TEST(ExrChecks, TiledPizFilesAreRefused) {
  std::vector<unsigned char> bytes = piz_file(16, 16, TINYEXR_PIXELTYPE_HALF);
  bytes.at(5) |= 0x02;  // the version field's "single-part tiled" bit (bit 9)
  const std::string tiles("tiles\0tiledesc\0\x09\0\0\0\x10\0\0\0\x10\0\0\0\0", 28);
  bytes.insert(bytes.begin() + 8, tiles.begin(), tiles.end());
  EXPECT_EQ(load_error(bytes, "tiled.exr"), "tiled.exr: tiled PIZ-compressed OpenEXR files are not supported");
}

}  // namespace
}  // namespace glint
