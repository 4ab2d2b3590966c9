#include "renderer/image_file.h"

#include "renderer/atomic_file.h"
#include "renderer/image.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <string_view>
#include <system_error>

namespace glint {
namespace {

// The formats of image.h, told apart by their signatures. stb knows more formats (TGA, PSD,
// PIC, ...) but they are neither needed nor as well exercised on broken input, so they are
// refused rather than half-supported.
std::optional<ImageFormat> sniff_format(const std::vector<unsigned char>& bytes) {
  auto starts_with = [&](std::string_view magic) {
    return bytes.size() >= magic.size() &&
           std::equal(magic.begin(), magic.end(), bytes.begin(),
                      [](char a, unsigned char b) { return static_cast<unsigned char>(a) == b; });
  };
  if (starts_with("\x89PNG\r\n\x1a\n")) return ImageFormat::png;
  if (starts_with("\xff\xd8\xff")) return ImageFormat::jpeg;
  if (starts_with("#?RADIANCE\n") || starts_with("#?RGBE\n")) return ImageFormat::radiance;
  if (starts_with(std::string_view("\x76\x2f\x31\x01", 4))) return ImageFormat::openexr;
  return std::nullopt;
}

}  // namespace

// The chunk layout and CRCs (PNG spec, ISO 15948 sections 5.3 and 15.3 / annex D: CRC-32 with
// polynomial 0xEDB88320, over type and data); trailing bytes after IEND are ignored as
// decoders do.
uint32_t png_crc(const unsigned char* data, size_t size, uint32_t crc) {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t n = 0; n < 256; ++n) {
      uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  for (size_t i = 0; i < size; ++i) crc = table[(crc ^ data[i]) & 0xff] ^ (crc >> 8);
  return crc;
}

void image_fail(const std::filesystem::path& path, const std::string& problem) {
  throw ImageError(path.string() + ": " + problem);
}

void check_image_dimensions(const std::filesystem::path& path, int width, int height) {
  if (width <= 0 || height <= 0)
    image_fail(path, "invalid image size " + std::to_string(width) + "x" + std::to_string(height));
  if (width > kMaxImageDimension || height > kMaxImageDimension)
    image_fail(path, "image is too large (" + std::to_string(width) + "x" + std::to_string(height) +
                         ", the limit is " + std::to_string(kMaxImageDimension) + " per side)");
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::vector<unsigned char> read_image_prefix(const std::filesystem::path& path, size_t max_bytes) {
  std::error_code ec;
  // exists() is false also when the path cannot be resolved (a symbolic link loop): give that
  // reason rather than "not found".
  if (!std::filesystem::exists(path, ec)) image_fail(path, ec ? ec.message() : "file not found");
  if (std::filesystem::is_directory(path, ec)) image_fail(path, "is a directory, not an image");
  // A FIFO or device (a texture path of /dev/stdin) would block or never end.
  if (!std::filesystem::is_regular_file(path, ec)) image_fail(path, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) image_fail(path, std::string("cannot open file: ") + std::strerror(errno));
  std::vector<unsigned char> bytes;
  char buffer[65536];
  while (bytes.size() < max_bytes) {
    in.read(buffer, static_cast<std::streamsize>(std::min(sizeof buffer, max_bytes - bytes.size())));
    bytes.insert(bytes.end(), buffer, buffer + in.gcount());
    if (in.gcount() == 0) break;
  }
  if (in.bad()) image_fail(path, "read error");
  if (bytes.empty()) image_fail(path, "file is empty");
  return bytes;
}

std::vector<unsigned char> read_image_file(const std::filesystem::path& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size >= static_cast<uintmax_t>(std::numeric_limits<int>::max()))
    image_fail(path, "file is too large");
  return read_image_prefix(path, std::numeric_limits<int>::max());
}

ImageFormat require_image_format(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
  const std::optional<ImageFormat> format = sniff_format(bytes);
  if (!format) image_fail(path, "not an image in a supported format (PNG, JPEG, Radiance HDR, OpenEXR)");
  return *format;
}

void check_png_chunks(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
  auto be32 = [&](size_t at) {
    return uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 |
           uint32_t(bytes[at + 2]) << 8 | uint32_t(bytes[at + 3]);
  };
  size_t at = 8;  // after the signature
  for (;;) {
    if (bytes.size() - at < 12) image_fail(path, "file is truncated (no IEND chunk)");
    const size_t length = be32(at);
    const std::string type(reinterpret_cast<const char*>(&bytes[at + 4]), 4);
    const std::string where = "chunk '" + type + "' at byte " + std::to_string(at);
    if (length > bytes.size() - at - 12) image_fail(path, "file is truncated (" + where + " runs past the end)");
    const uint32_t stored = be32(at + 8 + length);
    if ((png_crc(&bytes[at + 4], length + 4, 0xffffffffu) ^ 0xffffffffu) != stored)
      image_fail(path, "corrupt PNG (CRC mismatch in " + where + ")");
    if (type == "IEND") return;
    at += 12 + length;
  }
}

ImageFormat check_before_decoding(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
  if (bytes.empty()) image_fail(path, "file is empty");
  if (bytes.size() >= static_cast<size_t>(std::numeric_limits<int>::max())) image_fail(path, "file is too large");
  const ImageFormat format = require_image_format(path, bytes);
  if (format == ImageFormat::png) check_png_chunks(path, bytes);
  return format;
}

void write_image_file(const std::filesystem::path& path, const std::vector<unsigned char>& file) {
  try {
    write_file_atomically(path, file.data(), file.size());
  } catch (const FileWriteError& e) {
    image_fail(path, e.problem);
  }
}

}  // namespace glint
