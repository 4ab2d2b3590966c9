#include "renderer/exr_checks.h"

#include <algorithm>
#include <cstdint>

namespace glint {
namespace {

// Little-endian integers at `at`; the caller has checked that the bytes exist.
uint64_t read_u64(const std::vector<unsigned char>& b, size_t at) {
  uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = v << 8 | b[at + static_cast<size_t>(i)];
  return v;
}
uint32_t read_u32(const std::vector<unsigned char>& b, size_t at) {
  return uint32_t(b[at]) | uint32_t(b[at + 1]) << 8 | uint32_t(b[at + 2]) << 16 | uint32_t(b[at + 3]) << 24;
}
int32_t read_i32(const std::vector<unsigned char>& b, size_t at) { return static_cast<int32_t>(read_u32(b, at)); }
uint16_t read_u16(const std::vector<unsigned char>& b, size_t at) { return uint16_t(b[at] | b[at + 1] << 8); }

constexpr int kPizBitmapSize = 8192;   // tinyexr's BITMAP_SIZE (65536 / 8)
constexpr int64_t kHuffmanHeader = 20;  // im, iM, table length, nBits, reserved: 5 x 4 bytes

// What is wrong with PIZ block `data` of `size` bytes, or "".
std::string unsafe_piz_data(const std::vector<unsigned char>& b, size_t data, int64_t size) {
  if (size < 4) return "is " + std::to_string(size) + " bytes";
  const int min_non_zero = read_u16(b, data), max_non_zero = read_u16(b, data + 2);
  if (max_non_zero >= kPizBitmapSize) return "";  // tinyexr refuses it before reading on
  const int64_t bitmap = min_non_zero <= max_non_zero ? max_non_zero - min_non_zero + 1 : 0;
  if (4 + bitmap + 4 > size)
    return "is " + std::to_string(size) + " bytes, its bitmap needs " + std::to_string(4 + bitmap + 4);
  const int64_t huffman = read_i32(b, data + static_cast<size_t>(4 + bitmap));
  if (huffman < 0 || 4 + bitmap + 4 + huffman > size)
    return "has Huffman data of " + std::to_string(huffman) + " bytes in " + std::to_string(size);
  if (huffman > 0 && huffman < kHuffmanHeader)
    return "has Huffman data of " + std::to_string(huffman) + " bytes, shorter than its header";
  return "";
}

}  // namespace

std::string unsafe_exr_attribute(const std::vector<unsigned char>& bytes) {
  size_t at = 8;  // after the magic number and the version field
  while (at < bytes.size() && bytes[at] != 0) {
    const auto name_end = std::find(bytes.begin() + static_cast<std::ptrdiff_t>(at), bytes.end(), 0);
    if (name_end == bytes.end()) return "";
    const auto type_end = std::find(name_end + 1, bytes.end(), 0);
    if (type_end == bytes.end() || bytes.end() - type_end < 5) return "";
    const size_t size_at = static_cast<size_t>(type_end - bytes.begin()) + 1;
    const uint32_t size = read_u32(bytes, size_at);
    const std::string name(bytes.begin() + static_cast<std::ptrdiff_t>(at), name_end);
    if (name == "tiles" && size != 9)
      return "attribute 'tiles' is " + std::to_string(size) + " bytes, not 9";
    at = size_at + 4 + size;
  }
  return "";
}

std::string unsafe_offset_table(size_t file_size, size_t table_start, unsigned long long entries) {
  const unsigned long long room = file_size > table_start ? (file_size - table_start) / 8 : 0;
  if (entries <= room) return "";
  return "an offset table of " + std::to_string(entries) + " entries does not fit in the file's " +
         std::to_string(file_size) + " bytes";
}

unsigned long long level0_tiles(int width, int height, int tile_width, int tile_height) {
  if (tile_width < 1 || tile_height < 1 || width < 1 || height < 1) return 0;
  const unsigned long long across = (static_cast<unsigned long long>(width) + tile_width - 1) / tile_width;
  const unsigned long long down = (static_cast<unsigned long long>(height) + tile_height - 1) / tile_height;
  return across * down;
}

std::string unsafe_piz_blocks(const std::vector<unsigned char>& bytes, const ExrScanlineLayout& layout) {
  const uint64_t file = bytes.size();
  const uint64_t table_end = layout.table_start + 8 * uint64_t(std::max(0, layout.blocks));
  if (layout.blocks <= 0 || table_end > file) return "";  // tinyexr reports a short table
  for (int i = 0; i < layout.blocks; ++i) {
    const std::string block = "PIZ block " + std::to_string(i);
    const uint64_t offset = read_u64(bytes, layout.table_start + 8 * size_t(i));
    // tinyexr rebuilds a table with a zero entry by walking the blocks: not for PIZ files.
    if (offset < table_end || offset > file || file - offset < 8)
      return block + " is not inside the file (offset " + std::to_string(offset) + ")";
    const size_t at = static_cast<size_t>(offset);
    const int64_t line = int64_t(read_i32(bytes, at)) - layout.min_y;
    const int64_t size = read_i32(bytes, at + 4);
    if (line < 0 || line >= layout.height)
      return block + " starts on line " + std::to_string(line) + " of " + std::to_string(layout.height);
    if (size < 0 || uint64_t(size) > file - offset - 8)
      return block + " is " + std::to_string(size) + " bytes, past the end of the file";
    const int64_t lines = std::min<int64_t>(layout.lines_per_block, layout.height - line);
    if (size == int64_t(layout.width) * lines * layout.bytes_per_pixel) continue;  // stored raw
    if (const std::string wrong = unsafe_piz_data(bytes, at + 8, size); !wrong.empty())
      return block + " " + wrong;
  }
  return "";
}

}  // namespace glint
