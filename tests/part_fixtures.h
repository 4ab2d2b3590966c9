// Render part files for tests (renderer/render_part.h): the bytes of an OpenEXR header walked
// and patched, and large parts of zeros that take little disk but much memory to decode.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "renderer/image.h"
#include "renderer/render_part.h"
#include "tests/image_fixtures.h"

namespace glint::test {

inline uint32_t le32_at(const std::string& b, size_t at) {
  uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);  // x86 and ARM: little-endian, as OpenEXR
  return v;
}

inline void put_le32(std::string& b, size_t at, uint32_t v) { std::memcpy(b.data() + at, &v, 4); }

inline std::string le64(uint64_t v) {
  std::string s(8, '\0');
  std::memcpy(s.data(), &v, 8);
  return s;
}

// Where the data of attribute `name` starts in a single-part OpenEXR file (npos: absent), and
// with an empty name where the header ends (the offset table's first byte).
inline size_t exr_attribute_data(const std::string& b, const std::string& name) {
  size_t at = 8;  // magic number and version
  while (at < b.size() && b[at] != '\0') {
    const size_t name_end = b.find('\0', at), type_end = b.find('\0', name_end + 1);
    if (type_end == std::string::npos || type_end + 5 > b.size()) throw std::runtime_error("bad EXR header");
    const size_t data = type_end + 5;
    if (!name.empty() && b.compare(at, name_end - at, name) == 0) return data;
    at = data + le32_at(b, type_end + 1);
  }
  return name.empty() ? at + 1 : std::string::npos;
}

// A part of info.width x info.height zero pixels (height a multiple of 16) as save_part_image
// would write it, ZIP-compressed: save_part_image writes a strip of 16 lines with info's
// header; its one block is repeated for every 16 lines and the data and display windows are
// patched to the full height. A 16384x16384 part takes 5 MB on disk and 5 GiB to decode.
inline void write_zero_part(const std::filesystem::path& file, const PartInfo& info) {
  if (info.height % 16 != 0 || info.width < 16) throw std::invalid_argument("write_zero_part: height % 16, width >= 16");
  const Image strip{info.width, 16, std::vector<float>(size_t(info.width) * 16 * 4, 0.0f)};
  save_part_image(file, info, strip);
  std::string b = file_bytes(file);
  for (const char* window : {"dataWindow", "displayWindow"}) {
    const size_t box = exr_attribute_data(b, window);  // xmin, ymin, xmax, ymax
    if (box == std::string::npos) throw std::runtime_error("no EXR attribute " + std::string(window));
    put_le32(b, box + 12, uint32_t(info.height - 1));
  }
  const size_t table = exr_attribute_data(b, "");
  uint64_t first_block = 0;  // the strip's one entry in the offset table
  std::memcpy(&first_block, b.data() + table, 8);
  const size_t block_at = size_t(first_block);
  const std::string block_data = b.substr(block_at + 8, le32_at(b, block_at + 4));
  const size_t blocks = size_t(info.height) / 16;
  std::string out = b.substr(0, table);
  uint64_t offset = table + 8 * blocks;
  for (size_t i = 0; i < blocks; ++i, offset += 8 + block_data.size()) out += le64(offset);
  for (size_t i = 0; i < blocks; ++i) {
    std::string header(8, '\0');
    put_le32(header, 0, uint32_t(i * 16));
    put_le32(header, 4, uint32_t(block_data.size()));
    out += header + block_data;
  }
  write_file_bytes(file, out);
}

}  // namespace glint::test
