// Image files that pass the header probe but are not what they claim, made from files that
// save_image writes: shared by the unit and editor tests.
#pragma once

#include <array>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/image.h"

namespace glint::test {

inline std::string file_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void write_file_bytes(const std::filesystem::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
}

// CRC-32 of a PNG chunk's type and data (PNG spec, annex D).
inline uint32_t png_chunk_crc(const std::string& type_and_data) {
  uint32_t crc = 0xffffffffu;
  for (unsigned char byte : type_and_data) {
    crc ^= byte;
    for (int k = 0; k < 8; ++k) crc = (crc & 1) ? 0xedb88320u ^ (crc >> 1) : crc >> 1;
  }
  return crc ^ 0xffffffffu;
}

inline std::string be32(uint32_t v) {
  return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

// A PNG chunk of `type` with `data` and its right CRC.
inline std::string png_chunk(const std::string& type, const std::string& data) {
  return be32(static_cast<uint32_t>(data.size())) + type + data + be32(png_chunk_crc(type + data));
}

// The chunks of a PNG that save_image wrote: IHDR first, then IDAT(s), then IEND.
struct PngParts {
  std::string ihdr_data, idat_data;
};
inline PngParts png_parts(const std::string& png) {
  PngParts parts;
  for (size_t at = 8; at + 12 <= png.size();) {
    const uint32_t length = uint32_t(uint8_t(png[at])) << 24 | uint32_t(uint8_t(png[at + 1])) << 16 |
                            uint32_t(uint8_t(png[at + 2])) << 8 | uint32_t(uint8_t(png[at + 3]));
    const std::string type = png.substr(at + 4, 4);
    if (type == "IHDR") parts.ihdr_data = png.substr(at + 8, length);
    if (type == "IDAT") parts.idat_data += png.substr(at + 8, length);
    at += 12 + length;
  }
  if (parts.ihdr_data.size() != 13 || parts.idat_data.empty()) throw std::logic_error("not a PNG");
  return parts;
}

inline std::string png_from(const std::string& ihdr_data, const std::string& idat_data) {
  return "\x89PNG\r\n\x1a\n" + png_chunk("IHDR", ihdr_data) + png_chunk("IDAT", idat_data) +
         png_chunk("IEND", "");
}

// An 8-bit PNG whose header claims width x height but whose pixel data is that of a small
// image: valid chunks and CRCs (the probe accepts it), decodes to garbage or fails. A
// 16384x16384 one is a few hundred bytes.
inline void write_png_claiming(const std::filesystem::path& file, int width, int height) {
  Image small{2, 2, std::vector<float>(16, 0.5f)};
  save_image(file, small);
  PngParts parts = png_parts(file_bytes(file));
  parts.ihdr_data.replace(0, 8, be32(static_cast<uint32_t>(width)) + be32(static_cast<uint32_t>(height)));
  write_file_bytes(file, png_from(parts.ihdr_data, parts.idat_data));
}

// A PNG whose IDAT holds only the first half of its compressed pixels, with valid CRCs: it
// passes the probe and fails only when decoded.
inline void write_png_with_short_idat(const std::filesystem::path& file) {
  Image noise{32, 32, std::vector<float>(32 * 32 * 4)};
  for (size_t i = 0; i < noise.pixels.size(); ++i) noise.pixels[i] = float((i * 7919) % 251) / 250.0f;
  save_image(file, noise);
  PngParts parts = png_parts(file_bytes(file));
  write_file_bytes(file, png_from(parts.ihdr_data, parts.idat_data.substr(0, parts.idat_data.size() / 2)));
}

// An OpenEXR file of `image` whose channels are renamed a, b, g, r: a valid header with no R,
// G, B (nor a single grey channel), which only decoding refuses.
inline void write_exr_without_rgb(const std::filesystem::path& file, const Image& image) {
  save_image(file, image);
  std::string bytes = file_bytes(file);
  const std::string list("channels\0chlist\0", 16);
  size_t at = bytes.find(list);
  if (at == std::string::npos) throw std::logic_error("no channel list");
  at += list.size() + 4;  // the attribute's size
  // Each entry: a name ending in NUL, then pixel type, pLinear, reserved, x and y sampling.
  for (int c = 0; c < 4; ++c, at += 2 + 16) bytes.at(at) = char(std::tolower(bytes.at(at)));
  write_file_bytes(file, bytes);
}

}  // namespace glint::test
