#include "renderer/image_metadata.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <utility>

#include "renderer/image.h"
#include "renderer/image_file.h"
#include "renderer/state_file.h"

namespace glint {
namespace {

constexpr unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr char kRadianceMagic[] = "#?RADIANCE\n";
// The most header a Radiance file is searched for its lines (Radiance's own are a few lines).
constexpr size_t kMaxHdrHeader = 64 * 1024;
// Images Glint reads the metadata of: its own renders, at most 16384 a side (image_io.cpp).
constexpr size_t kMaxImageBytes = size_t(4) << 30;

[[noreturn]] void fail(const std::filesystem::path& label, const std::string& problem) {
  throw ImageError(label.string() + ": " + problem);
}

uint32_t crc32(const unsigned char* data, size_t size) { return png_crc(data, size, 0xffffffffu) ^ 0xffffffffu; }

uint32_t be32(const std::vector<unsigned char>& bytes, size_t at) {
  return uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 | uint32_t(bytes[at + 2]) << 8 |
         uint32_t(bytes[at + 3]);
}

void put_be32(std::vector<unsigned char>& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<unsigned char>(v >> shift));
}

bool is_ascii(const std::string& text) {
  for (unsigned char c : text)
    if (c >= 0x80) return false;
  return true;
}

// One chunk: length, type, data, CRC over type and data.
void append_chunk(std::vector<unsigned char>& out, const char* type, const std::string& data) {
  put_be32(out, static_cast<uint32_t>(data.size()));
  const size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put_be32(out, crc32(&out[start], out.size() - start));
}

// The (keyword, text) of a tEXt or iTXt chunk's data; nullopt for compressed iTXt text.
std::optional<std::pair<std::string, std::string>> text_chunk_entry(const std::string& type, const std::string& data,
                                                                    const std::filesystem::path& label,
                                                                    const std::string& where) {
  const size_t key_end = data.find('\0');
  if (key_end == std::string::npos || key_end == 0 || key_end > 79)
    fail(label, "corrupt PNG (" + where + " has no keyword of 1 to 79 characters)");
  if (type == "tEXt") return std::pair{data.substr(0, key_end), data.substr(key_end + 1)};
  // iTXt: keyword \0 compression-flag method language \0 translated-keyword \0 text
  const size_t language_end = data.size() < key_end + 3 ? std::string::npos : data.find('\0', key_end + 3);
  const size_t translated_end = language_end == std::string::npos ? language_end : data.find('\0', language_end + 1);
  if (translated_end == std::string::npos) fail(label, "corrupt PNG (" + where + " is cut short)");
  if (data[key_end + 1] != 0) return std::nullopt;
  return std::pair{data.substr(0, key_end), data.substr(translated_end + 1)};
}

void check_entries(const ImageMetadata& metadata) {
  for (const auto& [key, value] : metadata)
    if (const std::string why = metadata_entry_problem(key, value); !why.empty())
      throw std::invalid_argument("image metadata '" + key + "': " + why);
}

}  // namespace

std::string metadata_entry_problem(const std::string& key, const std::string& value) {
  if (key.empty() || key.size() > 79) return "a key has 1 to 79 characters";
  for (unsigned char c : key)
    if (c < 0x20 || c > 0x7e || c == '=') return "a key is printable ASCII without '='";
  if (key.front() == ' ' || key.back() == ' ' || key.find("  ") != std::string::npos)
    return "a key has no leading, trailing or double space";
  if (value.find_first_of(std::string("\0\r\n", 3)) != std::string::npos)
    return "a value has no NUL, CR or newline";
  return {};
}

std::vector<unsigned char> with_png_text(const std::vector<unsigned char>& png, const ImageMetadata& metadata) {
  check_entries(metadata);
  // The signature, then IHDR (13 bytes of data): text chunks go right after it.
  if (png.size() < 33 || std::memcmp(png.data(), kPngSignature, 8) != 0 || be32(png, 8) != 13 ||
      std::memcmp(&png[12], "IHDR", 4) != 0)
    throw std::invalid_argument("with_png_text: not a PNG beginning with IHDR");
  std::vector<unsigned char> out(png.begin(), png.begin() + 33);
  for (const auto& [key, value] : metadata) {
    if (is_ascii(value)) {
      append_chunk(out, "tEXt", key + '\0' + value);  // Latin-1, of which ASCII is a part
    } else {  // iTXt: keyword, no compression, no language or translated keyword, UTF-8 text
      append_chunk(out, "iTXt", key + std::string("\0\0\0\0\0", 5) + value);
    }
  }
  out.insert(out.end(), png.begin() + 33, png.end());
  return out;
}

std::vector<unsigned char> with_hdr_header_lines(const std::vector<unsigned char>& hdr,
                                                 const ImageMetadata& metadata) {
  check_entries(metadata);
  const size_t magic = sizeof kRadianceMagic - 1;
  if (hdr.size() < magic || std::memcmp(hdr.data(), kRadianceMagic, magic) != 0)
    throw std::invalid_argument("with_hdr_header_lines: not a Radiance file");
  std::vector<unsigned char> out(hdr.begin(), hdr.begin() + magic);
  for (const auto& [key, value] : metadata) {
    const std::string line = key + "=" + value + "\n";
    out.insert(out.end(), line.begin(), line.end());
  }
  out.insert(out.end(), hdr.begin() + magic, hdr.end());
  return out;
}

void check_image_metadata(const std::filesystem::path& path, const ImageMetadata& metadata) {
  for (const auto& [key, value] : metadata)
    if (const std::string why = metadata_entry_problem(key, value); !why.empty())
      fail(path, "metadata '" + key + "': " + why);
}

ImageMetadata read_png_text(const std::vector<unsigned char>& png, const std::filesystem::path& label) {
  if (png.size() < 8 || std::memcmp(png.data(), kPngSignature, 8) != 0) fail(label, "not a PNG file");
  ImageMetadata metadata;
  for (size_t at = 8;;) {
    if (png.size() - at < 12) fail(label, "file is truncated (no IEND chunk)");
    const size_t length = be32(png, at);
    const std::string type(reinterpret_cast<const char*>(&png[at + 4]), 4);
    const std::string where = "chunk '" + type + "' at byte " + std::to_string(at);
    if (length > png.size() - at - 12) fail(label, "file is truncated (" + where + " runs past the end)");
    if (crc32(&png[at + 4], length + 4) != be32(png, at + 8 + length))
      fail(label, "corrupt PNG (CRC mismatch in " + where + ")");
    if (type == "IEND") return metadata;
    if (type == "tEXt" || type == "iTXt") {
      const std::string data(reinterpret_cast<const char*>(&png[at + 8]), length);
      if (auto entry = text_chunk_entry(type, data, label, where)) metadata.push_back(std::move(*entry));
    }
    at += 12 + length;
  }
}

ImageMetadata read_hdr_header_lines(const std::vector<unsigned char>& hdr, const std::filesystem::path& label) {
  const std::string head(hdr.begin(), hdr.begin() + static_cast<std::ptrdiff_t>(std::min(hdr.size(), kMaxHdrHeader)));
  if (head.rfind("#?", 0) != 0) fail(label, "not a Radiance file (no #? first line)");
  const size_t end = head.find("\n\n");
  if (end == std::string::npos)
    fail(label, "Radiance header has no end (no empty line in its first " + std::to_string(kMaxHdrHeader) + " bytes)");
  ImageMetadata metadata;
  for (size_t at = head.find('\n') + 1; at < end + 1;) {
    const size_t line_end = head.find('\n', at);
    const std::string line = head.substr(at, line_end - at);
    at = line_end + 1;
    const size_t equals = line.find('=');
    if (line.empty() || line[0] == '#' || equals == std::string::npos || equals == 0) continue;
    metadata.emplace_back(line.substr(0, equals), line.substr(equals + 1));
  }
  return metadata;
}

ImageMetadata read_image_metadata(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".exr") return read_exr_header(path).attributes;
  std::optional<std::string> text;
  try {
    text = read_state_file(path, kMaxImageBytes);
  } catch (const StateFileError& e) {
    fail(path, e.problem);
  }
  if (!text) fail(path, "file not found");
  const std::vector<unsigned char> bytes(text->begin(), text->end());
  if (ext == ".png") return read_png_text(bytes, path);
  if (ext == ".hdr") return read_hdr_header_lines(bytes, path);
  fail(path, "no metadata reader for '" + ext + "' (.png, .hdr or .exr)");
}

}  // namespace glint
