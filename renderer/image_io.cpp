// Image readers and writers (see image.h). stb_image handles PNG/JPG/HDR (and the other formats
// it knows), tinyexr handles OpenEXR. Both libraries are linked as shared objects that already
// contain their implementations, so no *_IMPLEMENTATION macro is defined here.
#include "renderer/image.h"

#include "renderer/atomic_file.h"
#include "renderer/exr_checks.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <string_view>
#include <system_error>

#include <sys/mman.h>

#include <stb_image.h>
#include <stb_image_write.h>
#include <tinyexr.h>

namespace glint {
namespace {

// Larger images are refused before any pixel memory is allocated: a corrupt or hostile header
// must not make us allocate gigabytes.
constexpr int kMaxDimension = 16384;

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& problem) {
  throw ImageError(path.string() + ": " + problem);
}

void check_dimensions(const std::filesystem::path& path, int width, int height) {
  if (width <= 0 || height <= 0)
    fail(path, "invalid image size " + std::to_string(width) + "x" + std::to_string(height));
  if (width > kMaxDimension || height > kMaxDimension)
    fail(path, "image is too large (" + std::to_string(width) + "x" + std::to_string(height) +
                   ", the limit is " + std::to_string(kMaxDimension) + " per side)");
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::vector<unsigned char> read_file(const std::filesystem::path& path, size_t max_bytes) {
  std::error_code ec;
  // exists() is false also when the path cannot be resolved (a symbolic link loop): give that
  // reason rather than "not found".
  if (!std::filesystem::exists(path, ec)) fail(path, ec ? ec.message() : "file not found");
  if (std::filesystem::is_directory(path, ec)) fail(path, "is a directory, not an image");
  // A FIFO or device (a texture path of /dev/stdin) would block or never end.
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, std::string("cannot open file: ") + std::strerror(errno));
  std::vector<unsigned char> bytes;
  char buffer[65536];
  while (bytes.size() < max_bytes) {
    in.read(buffer, static_cast<std::streamsize>(std::min(sizeof buffer, max_bytes - bytes.size())));
    bytes.insert(bytes.end(), buffer, buffer + in.gcount());
    if (in.gcount() == 0) break;
  }
  if (in.bad()) fail(path, "read error");
  if (bytes.empty()) fail(path, "file is empty");
  return bytes;
}

enum class Format { png, jpeg, radiance, openexr };

// The formats of image.h, told apart by their signatures. stb knows more formats (TGA, PSD,
// PIC, ...) but they are neither needed nor as well exercised on broken input, so they are
// refused rather than half-supported.
std::optional<Format> sniff_format(const std::vector<unsigned char>& bytes) {
  auto starts_with = [&](std::string_view magic) {
    return bytes.size() >= magic.size() &&
           std::equal(magic.begin(), magic.end(), bytes.begin(),
                      [](char a, unsigned char b) { return static_cast<unsigned char>(a) == b; });
  };
  if (starts_with("\x89PNG\r\n\x1a\n")) return Format::png;
  if (starts_with("\xff\xd8\xff")) return Format::jpeg;
  if (starts_with("#?RADIANCE\n") || starts_with("#?RGBE\n")) return Format::radiance;
  if (starts_with(std::string_view("\x76\x2f\x31\x01", 4))) return Format::openexr;
  return std::nullopt;
}

Format require_format(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
  const std::optional<Format> format = sniff_format(bytes);
  if (!format) fail(path, "not an image in a supported format (PNG, JPEG, Radiance HDR, OpenEXR)");
  return *format;
}

// stb's decoders do not fail at the end of their input: they read zeros instead, so a truncated
// file can "load" with garbage, and the run-length .hdr decoder even loops forever on zeros
// (a zero run length makes no progress). So stb reads through these callbacks, which
//  - record whether it ever asked for bytes past the end (a valid file never does): a read that
//    finds nothing left, or a short answer to a direct read (stb_image reads exactly what it
//    needs directly, but refills its 128-byte buffer with whatever is left), and
//  - answer such reads with a bounded amount of 0xFF filler, on which every stb decoder makes
//    progress or fails (0xFF is a run of 127 in .hdr), before reporting a real end of file.
struct StbSource {
  static constexpr int kStbBufferSize = 128;  // stbi__context::buffer_start
  const unsigned char* data = nullptr;
  size_t size = 0;
  size_t pos = 0;
  size_t filler_left = 0;
  bool overrun = false;

  static int read(void* user, char* out, int count) {
    auto* s = static_cast<StbSource*>(user);
    if (count <= 0) return 0;
    size_t n = std::min(static_cast<size_t>(count), s->size - s->pos);
    std::memcpy(out, s->data + s->pos, n);
    s->pos += n;
    if (n < static_cast<size_t>(count) && count != kStbBufferSize) s->overrun = true;
    if (n == 0) {
      s->overrun = true;
      n = std::min(static_cast<size_t>(count), s->filler_left);
      std::memset(out, 0xff, n);
      s->filler_left -= n;
    }
    return static_cast<int>(n);
  }
  static void skip(void* user, int count) {
    auto* s = static_cast<StbSource*>(user);
    if (count > 0 && static_cast<size_t>(count) > s->size - s->pos) {
      s->overrun = true;
      s->pos = s->size;
    } else if (count < 0 && static_cast<size_t>(-static_cast<long long>(count)) > s->pos) {
      s->pos = 0;  // stb never skips backwards past the start; be safe anyway
    } else {
      s->pos = static_cast<size_t>(static_cast<long long>(s->pos) + count);
    }
  }
  static int eof(void* user) {
    auto* s = static_cast<StbSource*>(user);
    return s->pos >= s->size;
  }
  static constexpr stbi_io_callbacks callbacks{&read, &skip, &eof};

  // `filler` bounds the bytes handed out past the end: enough for a decoder to run through
  // every remaining pixel (a few bytes each), so that it finishes instead of looping.
  StbSource(const std::vector<unsigned char>& bytes, size_t filler)
      : data(bytes.data()), size(bytes.size()), filler_left(filler) {}
};

std::string stb_reason() {
  const char* reason = stbi_failure_reason();
  return reason ? reason : "unknown error";
}

struct StbInfo {
  int width = 0, height = 0, channels = 0;
  bool is_hdr = false, is_16_bit = false;
};

StbInfo stb_info(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
  constexpr size_t kFiller = 65536;
  StbInfo info;
  StbSource source(bytes, kFiller);
  const bool ok = stbi_info_from_callbacks(&StbSource::callbacks, &source, &info.width,
                                           &info.height, &info.channels) != 0;
  if (source.overrun) fail(path, "file is truncated (incomplete image header)");
  if (!ok) fail(path, "not a readable image (" + stb_reason() + ")");
  StbSource hdr(bytes, kFiller);
  info.is_hdr = stbi_is_hdr_from_callbacks(&StbSource::callbacks, &hdr) != 0;
  StbSource deep(bytes, kFiller);
  info.is_16_bit = stbi_is_16_bit_from_callbacks(&StbSource::callbacks, &deep) != 0;
  return info;
}

// Exact sRGB decode of each 8-bit value (a table: it is used for every texel).
const std::array<float, 256>& srgb_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[i] = srgb_to_linear(static_cast<float>(i) / 255.0f);
    return t;
  }();
  return table;
}

// Expands 1-4 channel data to RGBA; `convert(value, is_alpha)` maps a stored sample to linear.
template <typename T, typename Convert>
Image expand_to_rgba(const T* data, int width, int height, int channels, Convert convert) {
  Image image;
  image.width = width;
  image.height = height;
  const size_t count = static_cast<size_t>(width) * height;
  image.pixels.resize(count * 4);
  for (size_t i = 0; i < count; ++i) {
    const T* in = data + i * channels;
    float* out = &image.pixels[i * 4];
    if (channels <= 2) {
      out[0] = out[1] = out[2] = convert(in[0], false);
    } else {
      for (int c = 0; c < 3; ++c) out[c] = convert(in[c], false);
    }
    out[3] = (channels == 2 || channels == 4) ? convert(in[channels - 1], true) : 1.0f;
  }
  return image;
}

// Runs one stb loader (8-bit, 16-bit or float) and expands its result to linear RGBA.
template <typename T, typename Load, typename Convert>
Image decode_stb(const std::filesystem::path& path, StbSource& source, Load load,
                 Convert convert) {
  int width = 0, height = 0, channels = 0;
  // Native channel count (desired 0): grey and grey+alpha are expanded here, not by stb.
  std::unique_ptr<T, decltype(&stbi_image_free)> data(
      load(&StbSource::callbacks, &source, &width, &height, &channels, 0), &stbi_image_free);
  // Past the end stb reads filler and may fail on it: the real problem is then the truncation.
  if (source.overrun) fail(path, "file is truncated");
  if (!data) fail(path, "cannot decode image (" + stb_reason() + ")");
  check_dimensions(path, width, height);
  if (channels < 1 || channels > 4) fail(path, "unsupported channel count");
  return expand_to_rgba(data.get(), width, height, channels, convert);
}

Image load_stb(const std::filesystem::path& path, const std::vector<unsigned char>& bytes,
               ColorEncoding encoding) {
  const StbInfo info = stb_info(path, bytes);
  check_dimensions(path, info.width, info.height);
  // Only the .hdr decoder needs filler to finish (at most 4 bytes per pixel).
  StbSource source(bytes, info.is_hdr ? 4 * static_cast<size_t>(info.width) * info.height : 0);
  if (info.is_hdr)
    return decode_stb<float>(path, source, stbi_loadf_from_callbacks,
                             [](float v, bool) { return v; });
  if (info.is_16_bit)
    return decode_stb<stbi_us>(path, source, stbi_load_16_from_callbacks,
                               [](stbi_us v, bool) { return static_cast<float>(v) / 65535.0f; });
  const auto& table = srgb_table();
  const bool srgb = encoding == ColorEncoding::srgb;
  return decode_stb<stbi_uc>(path, source, stbi_load_from_callbacks, [&](stbi_uc v, bool alpha) {
    return srgb && !alpha ? table[v] : static_cast<float>(v) / 255.0f;
  });
}

// An 8-bit image kept 8-bit: RGBA as stored (grey becomes (g, g, g), missing alpha 255).
TextureImage load_stb_rgba8(const std::filesystem::path& path,
                            const std::vector<unsigned char>& bytes) {
  StbSource source(bytes, 0);
  int width = 0, height = 0, channels = 0;
  std::unique_ptr<stbi_uc, decltype(&stbi_image_free)> data(
      stbi_load_from_callbacks(&StbSource::callbacks, &source, &width, &height, &channels, 0),
      &stbi_image_free);
  if (source.overrun) fail(path, "file is truncated");
  if (!data) fail(path, "cannot decode image (" + stb_reason() + ")");
  check_dimensions(path, width, height);
  if (channels < 1 || channels > 4) fail(path, "unsupported channel count");
  TextureImage texture;
  texture.linear.width = width;
  texture.linear.height = height;
  const size_t count = static_cast<size_t>(width) * height;
  texture.rgba8.resize(count * 4);
  for (size_t i = 0; i < count; ++i) {
    const stbi_uc* in = data.get() + i * channels;
    unsigned char* out = &texture.rgba8[i * 4];
    for (int c = 0; c < 3; ++c) out[c] = channels <= 2 ? in[0] : in[c];
    out[3] = (channels == 2 || channels == 4) ? in[channels - 1] : 255;
  }
  return texture;
}

// A texel that no light or colour can have: NaN or Inf blackens whatever it reaches (the
// renderer discards non-finite samples) and a negative one makes negative radiance.
void check_texels(const std::filesystem::path& path, const Image& image) {
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const float v = image.pixels[i];
    if (std::isfinite(v) && v >= 0.0f) continue;
    const size_t texel = i / 4;
    char text[160];
    std::snprintf(text, sizeof text, "texel (%zu, %zu) channel %c is %g (texels must be finite and not negative)",
                  texel % static_cast<size_t>(image.width), texel / static_cast<size_t>(image.width),
                  "RGBA"[i % 4], static_cast<double>(v));
    fail(path, text);
  }
}

// stb_image checks neither the CRC of PNG chunks nor zlib's Adler-32, so a corrupted file can
// decode to wrong pixels without an error. The chunk layout and CRCs (PNG spec, ISO 15948
// sections 5.3 and 15.3 / annex D: CRC-32 with polynomial 0xEDB88320, over type and data) are
// checked here first; trailing bytes after IEND are ignored as decoders do.
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

void check_png_chunks(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
  auto be32 = [&](size_t at) {
    return uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 |
           uint32_t(bytes[at + 2]) << 8 | uint32_t(bytes[at + 3]);
  };
  size_t at = 8;  // after the signature
  for (;;) {
    if (bytes.size() - at < 12) fail(path, "file is truncated (no IEND chunk)");
    const size_t length = be32(at);
    const std::string type(reinterpret_cast<const char*>(&bytes[at + 4]), 4);
    const std::string where = "chunk '" + type + "' at byte " + std::to_string(at);
    if (length > bytes.size() - at - 12) fail(path, "file is truncated (" + where + " runs past the end)");
    const uint32_t stored = be32(at + 8 + length);
    if ((png_crc(&bytes[at + 4], length + 4, 0xffffffffu) ^ 0xffffffffu) != stored)
      fail(path, "corrupt PNG (CRC mismatch in " + where + ")");
    if (type == "IEND") return;
    at += 12 + length;
  }
}

// --- OpenEXR -----------------------------------------------------------------------------------

// Owns a parsed tinyexr header and image so that every exit path frees them.
struct ExrFile {
  EXRVersion version{};
  EXRHeader header{};
  EXRImage image{};
  bool image_loaded = false;
  ExrFile() {
    InitEXRHeader(&header);
    InitEXRImage(&image);
  }
  ~ExrFile() {
    if (image_loaded) FreeEXRImage(&image);
    FreeEXRHeader(&header);
  }
  ExrFile(const ExrFile&) = delete;
  ExrFile& operator=(const ExrFile&) = delete;
};

std::string take_exr_error(const char* err, int code) {
  std::string message = err ? err : "error code " + std::to_string(code);
  if (err) FreeEXRErrorMessage(err);
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  return message;
}

void parse_exr_header(const std::filesystem::path& path, const std::vector<unsigned char>& bytes,
                      ExrFile& exr) {
  int ret = ParseEXRVersionFromMemory(&exr.version, bytes.data(), bytes.size());
  if (ret != TINYEXR_SUCCESS) fail(path, "not a readable OpenEXR file (bad version field)");
  if (exr.version.multipart || exr.version.non_image)
    fail(path, "multi-part and deep OpenEXR files are not supported");
  if (const std::string unsafe = unsafe_exr_attribute(bytes); !unsafe.empty())
    fail(path, "bad OpenEXR header (" + unsafe + ")");
  const char* err = nullptr;
  ret = ParseEXRHeaderFromMemory(&exr.header, &exr.version, bytes.data(), bytes.size(), &err);
  if (ret != TINYEXR_SUCCESS) fail(path, "bad OpenEXR header (" + take_exr_error(err, ret) + ")");
  const EXRBox2i& box = exr.header.data_window;
  // 64-bit arithmetic: the window corners come straight from the file.
  const long long w = static_cast<long long>(box.max_x) - box.min_x + 1;
  const long long h = static_cast<long long>(box.max_y) - box.min_y + 1;
  check_dimensions(path, static_cast<int>(std::clamp<long long>(w, -1, kMaxDimension + 1)),
                   static_cast<int>(std::clamp<long long>(h, -1, kMaxDimension + 1)));
}

// A header that parse_exr_header accepted, as image.h describes it.
ExrHeaderInfo header_info(const EXRHeader& header) {
  ExrHeaderInfo info;
  info.min_x = header.data_window.min_x;
  info.min_y = header.data_window.min_y;
  info.width = header.data_window.max_x - header.data_window.min_x + 1;
  info.height = header.data_window.max_y - header.data_window.min_y + 1;
  for (int c = 0; c < header.num_channels; ++c) {
    const int type = header.pixel_types[c];
    info.channels.push_back({header.channels[c].name, type == TINYEXR_PIXELTYPE_HALF    ? ExrPixelType::half
                                                      : type == TINYEXR_PIXELTYPE_FLOAT ? ExrPixelType::float32
                                                                                        : ExrPixelType::uint32});
  }
  for (int i = 0; i < header.num_custom_attributes; ++i) {
    const EXRAttribute& a = header.custom_attributes[i];
    if (std::string(a.type) != "string" || a.size < 0) continue;
    std::string value;
    if (a.value) value.assign(reinterpret_cast<const char*>(a.value), static_cast<size_t>(a.size));
    while (!value.empty() && value.back() == '\0') value.pop_back();
    info.attributes.emplace_back(a.name, value);
  }
  return info;
}

// tinyexr allocates each channel's pixels with malloc and does not check the result: where the
// memory is not there (under an address-space limit) it writes through a null pointer. The
// same blocks are mapped, all at once, and unmapped first, so that a shortage is an error
// naming the file. (Large blocks are what malloc maps this way too.)
void check_decode_memory(const std::filesystem::path& path, const EXRHeader& header, int width, int height) {
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
  std::vector<std::pair<void*, size_t>> mapped;
  mapped.reserve(static_cast<size_t>(header.num_channels));
  size_t total = 0;
  bool enough = true;
  for (int c = 0; c < header.num_channels && enough; ++c) {
    const size_t bytes = pixels * (header.requested_pixel_types[c] == TINYEXR_PIXELTYPE_HALF ? 2 : 4);
    total += bytes;
    void* block = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (block == MAP_FAILED) enough = false;
    else mapped.emplace_back(block, bytes);
  }
  for (const auto& [block, bytes] : mapped) munmap(block, bytes);
  if (!enough)
    fail(path, "not enough memory to decode its " + std::to_string(width) + "x" + std::to_string(height) +
                   " pixels (" + std::to_string(total >> 20) + " MiB for " + std::to_string(header.num_channels) +
                   " channels)");
}

// The unnamed layer (R, G, B, A or a grey channel) or, with `layer`, its channels layer.R/G/B
// (or layer.X/Y/Z) and layer.A. `alpha_channel` (when given) names the channel read as alpha
// instead of A, and is required; `attributes` (when given) receives the header's string
// attributes; `before_decoding` (when given) is called with the header first.
Image load_exr(const std::filesystem::path& path, const std::vector<unsigned char>& bytes,
               const std::string& layer = "", const std::string& alpha_channel = "",
               ExrAttributes* attributes = nullptr, const ExrHeaderCheck& before_decoding = nullptr) {
  const std::string prefix = layer.empty() ? "" : layer + ".";
  ExrFile exr;
  parse_exr_header(path, bytes, exr);
  EXRHeader& header = exr.header;
  if (attributes || before_decoding) {
    ExrHeaderInfo info = header_info(header);
    if (before_decoding) before_decoding(info);
    if (attributes) *attributes = std::move(info.attributes);
  }
  int index[4] = {-1, -1, -1, -1};  // R, G, B, A
  int luminance = -1;
  for (int c = 0; c < header.num_channels; ++c) {
    const EXRChannelInfo& channel = header.channels[c];
    if (channel.x_sampling != 1 || channel.y_sampling != 1)
      fail(path, "sub-sampled OpenEXR channels are not supported");
    const std::string name = channel.name;
    if (name == prefix + "R" || (!layer.empty() && name == prefix + "X")) index[0] = c;
    if (name == prefix + "G" || (!layer.empty() && name == prefix + "Y")) index[1] = c;
    if (name == prefix + "B" || (!layer.empty() && name == prefix + "Z")) index[2] = c;
    if (name == (alpha_channel.empty() ? prefix + "A" : alpha_channel)) index[3] = c;
    if (layer.empty() && name == "Y") luminance = c;
    // Everything is read as float; UINT channels cannot be converted by tinyexr.
    if (header.pixel_types[c] == TINYEXR_PIXELTYPE_HALF)
      header.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
    else if (header.pixel_types[c] == TINYEXR_PIXELTYPE_UINT)
      fail(path, "integer OpenEXR channel '" + name + "' is not supported");
  }
  if (!alpha_channel.empty() && index[3] < 0) fail(path, "OpenEXR file has no '" + alpha_channel + "' channel");
  // A single channel of any name, or Y, is grey.
  if (header.num_channels == 1 && luminance < 0 && layer.empty()) luminance = 0;
  if (!layer.empty() && (index[0] < 0 || index[1] < 0 || index[2] < 0))
    fail(path, "OpenEXR file has no layer '" + layer + "' (channels " + prefix + "R/G/B or X/Y/Z)");
  if (index[0] < 0 || index[1] < 0 || index[2] < 0) {
    if (luminance < 0) fail(path, "OpenEXR file has neither R, G, B nor a single grey channel");
    index[0] = index[1] = index[2] = luminance;
  }

  // tinyexr allocates the offset table that the header implies before reading it, and its PIZ
  // decoder reads past a malformed block (exr_checks.h): both are checked first, and a PIZ file
  // is decoded from a copy with padding.
  const int width = header.data_window.max_x - header.data_window.min_x + 1;
  const int height = header.data_window.max_y - header.data_window.min_y + 1;
  const size_t table_start = 8 + size_t(header.header_len);
  unsigned long long entries = 0;  // 0: the table follows from the height alone (small)
  if (header.tiled) {
    entries = level0_tiles(width, height, header.tile_size_x, header.tile_size_y);
    if (entries == 0) fail(path, "bad OpenEXR header (tile size " + std::to_string(header.tile_size_x) + "x" +
                                     std::to_string(header.tile_size_y) + ")");
  } else if (header.chunk_count > 0) {
    entries = static_cast<unsigned long long>(header.chunk_count);
  }
  if (const std::string unsafe = unsafe_offset_table(bytes.size(), table_start, entries); !unsafe.empty())
    fail(path, "bad OpenEXR header (" + unsafe + ")");
  std::vector<unsigned char> padded;
  if (header.compression_type == TINYEXR_COMPRESSIONTYPE_PIZ) {
    if (header.tiled) fail(path, "tiled PIZ-compressed OpenEXR files are not supported");
    ExrScanlineLayout layout;
    layout.table_start = table_start;
    layout.min_y = header.data_window.min_y;
    layout.width = width;
    layout.height = height;
    layout.blocks = header.chunk_count > 0 ? header.chunk_count
                                           : (height + layout.lines_per_block - 1) / layout.lines_per_block;
    for (int c = 0; c < header.num_channels; ++c)
      layout.bytes_per_pixel += header.pixel_types[c] == TINYEXR_PIXELTYPE_HALF ? 2 : 4;
    if (const std::string unsafe = unsafe_piz_blocks(bytes, layout); !unsafe.empty())
      fail(path, "corrupt OpenEXR data (" + unsafe + ")");
    padded = bytes;
    padded.resize(bytes.size() + kPizReadPadding, 0);
  }
  // tinyexr frees a half-decoded image itself when decoding fails, but only the channels that
  // exr.image.num_channels counts, which it sets on success: preset it so that nothing leaks.
  exr.image.num_channels = header.num_channels;
  check_decode_memory(path, header, width, height);
  const char* err = nullptr;
  int ret = TINYEXR_ERROR_INVALID_DATA;
  try {
    ret = LoadEXRImageFromMemory(&exr.image, &header, padded.empty() ? bytes.data() : padded.data(), bytes.size(),
                                 &err);
  } catch (const std::bad_alloc&) {
    exr.image_loaded = true;  // frees the channels it allocated
    fail(path, "not enough memory to decode its " + std::to_string(width) + "x" + std::to_string(height) + " pixels");
  }
  if (ret != TINYEXR_SUCCESS) fail(path, "cannot decode OpenEXR data (" + take_exr_error(err, ret) + ")");
  exr.image_loaded = true;

  Image image;
  image.width = exr.image.width;
  image.height = exr.image.height;
  check_dimensions(path, image.width, image.height);
  image.pixels.assign(static_cast<size_t>(image.width) * image.height * 4, 1.0f);
  // Copies one block of rows/tiles: `channels[c]` holds block_w x block_h floats.
  auto copy_block = [&](unsigned char** channels, int x0, int y0, int block_w, int block_h) {
    for (int y = 0; y < block_h && y0 + y < image.height; ++y)
      for (int x = 0; x < block_w && x0 + x < image.width; ++x) {
        float* out = image.at(x0 + x, y0 + y);
        const size_t src = static_cast<size_t>(y) * block_w + x;
        for (int c = 0; c < 4; ++c)
          if (index[c] >= 0) out[c] = reinterpret_cast<const float*>(channels[index[c]])[src];
      }
  };
  if (header.tiled) {
    if (!exr.image.tiles) fail(path, "OpenEXR file has no tiles");
    for (int t = 0; t < exr.image.num_tiles; ++t) {
      const EXRTile& tile = exr.image.tiles[t];
      // The tile buffers are tile_size_x wide even when the tile is clipped at the border.
      copy_block(tile.images, tile.offset_x * header.tile_size_x,
                 tile.offset_y * header.tile_size_y, header.tile_size_x,
                 std::min(tile.height, header.tile_size_y));
    }
  } else {
    if (!exr.image.images) fail(path, "OpenEXR file has no pixel data");
    copy_block(exr.image.images, 0, 0, image.width, image.height);
  }
  return image;
}

ImageInfo probe_bytes(const std::filesystem::path& path, const std::vector<unsigned char>& bytes,
                      Format format) {
  if (format == Format::openexr) {
    ExrFile exr;
    parse_exr_header(path, bytes, exr);  // also checks the size
    const EXRBox2i& box = exr.header.data_window;
    return {box.max_x - box.min_x + 1, box.max_y - box.min_y + 1, exr.header.num_channels, true};
  }
  const StbInfo stb = stb_info(path, bytes);
  check_dimensions(path, stb.width, stb.height);
  return {stb.width, stb.height, stb.channels, stb.is_hdr || stb.is_16_bit};
}

// --- writing -----------------------------------------------------------------------------------

// The encoders write into memory; write_file_atomically then checks every write to the disk.
void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<unsigned char>*>(context);
  out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
}

std::vector<unsigned char> encode_png(const std::filesystem::path& path, const Image& image) {
  const size_t count = static_cast<size_t>(image.width) * image.height;
  // RGB when the image is opaque (smaller files), RGBA otherwise.
  bool has_alpha = false;
  for (size_t i = 0; i < count && !has_alpha; ++i) has_alpha = image.pixels[i * 4 + 3] < 1.0f;
  const int comp = has_alpha ? 4 : 3;
  std::vector<unsigned char> bytes(count * comp);
  for (size_t i = 0; i < count; ++i)
    for (int c = 0; c < comp; ++c) {
      const float v = image.pixels[i * 4 + c];
      // NaN fails the comparison and becomes 0.
      const float clamped = v > 0.0f ? std::min(v, 1.0f) : 0.0f;
      bytes[i * comp + c] = static_cast<unsigned char>(std::lround(clamped * 255.0f));
    }
  std::vector<unsigned char> file;
  if (!stbi_write_png_to_func(&append_bytes, &file, image.width, image.height, comp, bytes.data(),
                              image.width * comp))
    fail(path, "cannot encode the PNG image");
  return file;
}

std::vector<unsigned char> encode_hdr(const std::filesystem::path& path, const Image& image) {
  const size_t count = static_cast<size_t>(image.width) * image.height;
  // RGBE stores neither negative nor non-finite values, and its exponent tops out near 1e38.
  std::vector<float> rgb(count * 3);
  for (size_t i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c) {
      const float v = image.pixels[i * 4 + c];
      rgb[i * 3 + c] = v > 0.0f ? std::min(v, 1e38f) : 0.0f;
    }
  std::vector<unsigned char> file;
  if (!stbi_write_hdr_to_func(&append_bytes, &file, image.width, image.height, 3, rgb.data()))
    fail(path, "cannot encode the Radiance HDR image");
  return file;
}

// RGBA float32 as tinyexr's SaveEXR writes it (the same bytes): channels in A, B, G, R order
// as most viewers expect, ZIP compressed unless the image is smaller than 16x16.
// Every layer's channels as float32, sorted by name as OpenEXR requires; `attributes` are
// written as string attributes.
std::vector<unsigned char> encode_exr_layers(const std::filesystem::path& path,
                                             const std::vector<ExrLayer>& layers,
                                             const ExrAttributes& attributes = {}) {
  struct Channel {
    std::string name;
    const Image* image;
    int component;
  };
  std::vector<Channel> list;
  for (const ExrLayer& layer : layers) {
    const Image& image = *layer.image;
    if (image.width != layers[0].image->width || image.height != layers[0].image->height ||
        image.pixels.size() != static_cast<size_t>(image.width) * image.height * 4)
      fail(path, "the layers of an OpenEXR file must have one size");
    if (layer.single_component >= 0) {
      list.push_back({layer.name, &image, std::min(layer.single_component, 3)});
      continue;
    }
    for (size_t c = 0; c < layer.channels.size() && c < 4; ++c)
      list.push_back({(layer.name.empty() ? "" : layer.name + ".") + layer.channels[c], &image,
                      static_cast<int>(c)});
  }
  std::sort(list.begin(), list.end(), [](const Channel& a, const Channel& b) { return a.name < b.name; });
  const int width = layers[0].image->width, height = layers[0].image->height;
  const size_t count = static_cast<size_t>(width) * height;
  const size_t n = list.size();
  std::vector<std::vector<float>> planes(n);
  std::vector<unsigned char*> pointers(n);
  std::vector<EXRChannelInfo> channels(n);
  std::vector<int> pixel_types(n, TINYEXR_PIXELTYPE_FLOAT), requested_types(n, TINYEXR_PIXELTYPE_FLOAT);
  for (size_t c = 0; c < n; ++c) {
    planes[c].resize(count);
    for (size_t i = 0; i < count; ++i) planes[c][i] = list[c].image->pixels[i * 4 + list[c].component];
    pointers[c] = reinterpret_cast<unsigned char*>(planes[c].data());
    channels[c] = EXRChannelInfo{};
    if (list[c].name.size() >= sizeof channels[c].name) fail(path, "OpenEXR channel name too long: " + list[c].name);
    std::copy(list[c].name.begin(), list[c].name.end(), channels[c].name);
  }
  if (attributes.size() > TINYEXR_MAX_CUSTOM_ATTRIBUTES) fail(path, "too many OpenEXR attributes");
  std::vector<EXRAttribute> custom(attributes.size());
  for (size_t i = 0; i < attributes.size(); ++i) {
    const auto& [name, value] = attributes[i];
    if (name.size() >= sizeof custom[i].name) fail(path, "OpenEXR attribute name too long: " + name);
    std::snprintf(custom[i].name, sizeof custom[i].name, "%s", name.c_str());
    std::snprintf(custom[i].type, sizeof custom[i].type, "string");
    custom[i].value = reinterpret_cast<unsigned char*>(const_cast<char*>(value.data()));
    custom[i].size = static_cast<int>(value.size());
  }
  EXRImage exr_image;
  InitEXRImage(&exr_image);
  exr_image.num_channels = static_cast<int>(n);
  exr_image.images = pointers.data();
  exr_image.width = width;
  exr_image.height = height;
  EXRHeader header;
  InitEXRHeader(&header);
  header.compression_type = width < 16 && height < 16 ? TINYEXR_COMPRESSIONTYPE_NONE
                                                       : TINYEXR_COMPRESSIONTYPE_ZIP;
  header.num_channels = static_cast<int>(n);
  header.channels = channels.data();
  header.num_custom_attributes = static_cast<int>(custom.size());
  header.custom_attributes = custom.empty() ? nullptr : custom.data();
  header.pixel_types = pixel_types.data();
  header.requested_pixel_types = requested_types.data();
  unsigned char* memory = nullptr;
  const char* err = nullptr;
  const size_t size = SaveEXRImageToMemory(&exr_image, &header, &memory, &err);
  if (size == 0 || !memory) fail(path, "cannot encode the OpenEXR image (" + take_exr_error(err, 0) + ")");
  std::vector<unsigned char> file(memory, memory + size);
  std::free(memory);
  return file;
}

std::vector<unsigned char> encode_exr(const std::filesystem::path& path, const Image& image) {
  return encode_exr_layers(path, {ExrLayer{"", &image, "RGBA"}});
}

}  // namespace

float srgb_to_linear(float c) {
  if (c <= 0.04045f) return c / 12.92f;
  return std::pow((c + 0.055f) / 1.055f, 2.4f);
}

float linear_to_srgb(float c) {
  if (c <= 0.0031308f) return c * 12.92f;
  return 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

ImageInfo probe_image(const std::filesystem::path& path) {
  // Headers sit at the start of the file: read a prefix, and all of it only when the header
  // does not fit (an EXR with many attributes, a JPEG with large EXIF or ICC blocks).
  constexpr size_t kPrefix = 65536;
  std::vector<unsigned char> bytes = read_file(path, kPrefix);
  const Format format = require_format(path, bytes);
  if (format == Format::png) {
    // The whole file: its chunk CRCs are cheap to check and catch corruption anywhere, so a
    // project with a damaged texture is refused when it is opened, not when it is rendered.
    if (bytes.size() == kPrefix) bytes = read_file(path, std::numeric_limits<int>::max());
    check_png_chunks(path, bytes);
  }
  if (bytes.size() == kPrefix) {
    try {
      return probe_bytes(path, bytes, format);
    } catch (const ImageError&) {
      bytes = read_file(path, std::numeric_limits<int>::max());
    }
  }
  return probe_bytes(path, bytes, format);
}

// What every decoder needs first: a non-empty file that stb's int lengths can hold, of a known
// format, and for PNG intact chunks (check_png_chunks).
static Format check_before_decoding(const std::filesystem::path& path,
                                    const std::vector<unsigned char>& bytes) {
  if (bytes.empty()) fail(path, "file is empty");
  if (bytes.size() >= static_cast<size_t>(std::numeric_limits<int>::max())) fail(path, "file is too large");
  const Format format = require_format(path, bytes);
  if (format == Format::png) check_png_chunks(path, bytes);
  return format;
}

// The whole file for a decoder. stb takes an int length, so files of 2 GiB or more are refused
// up front.
static std::vector<unsigned char> read_image_file(const std::filesystem::path& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size >= static_cast<uintmax_t>(std::numeric_limits<int>::max()))
    fail(path, "file is too large");
  return read_file(path, std::numeric_limits<int>::max());
}

Image load_image(const std::filesystem::path& path, ColorEncoding encoding) {
  return load_image_data(read_image_file(path), path, encoding);
}

TextureImage load_texture_image(const std::filesystem::path& path) {
  return load_texture_image_data(read_image_file(path), path);
}

TextureImage load_texture_image_data(const std::vector<unsigned char>& bytes,
                                     const std::filesystem::path& path) {
  const Format format = check_before_decoding(path, bytes);
  TextureImage texture;
  if (format != Format::openexr) {
    const StbInfo info = stb_info(path, bytes);
    check_dimensions(path, info.width, info.height);
    if (!info.is_hdr && !info.is_16_bit) return load_stb_rgba8(path, bytes);
    texture.linear = load_stb(path, bytes, ColorEncoding::linear);
  } else {
    texture.linear = load_exr(path, bytes);
  }
  check_texels(path, texture.linear);
  return texture;
}

float TextureImage::value(int x, int y, int c, ColorEncoding encoding) const {
  const size_t i = (static_cast<size_t>(y) * linear.width + x) * 4 + c;
  if (!eight_bit()) return linear.pixels[i];
  return encoding == ColorEncoding::srgb && c < 3 ? srgb_table()[rgba8[i]]
                                                  : static_cast<float>(rgba8[i]) / 255.0f;
}

Image to_linear_image(const TextureImage& texture, ColorEncoding encoding) {
  if (!texture.eight_bit()) return texture.linear;
  Image image;
  image.width = texture.width();
  image.height = texture.height();
  image.pixels.resize(texture.rgba8.size());
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 4; ++c) image.at(x, y)[c] = texture.value(x, y, c, encoding);
  return image;
}

Image load_image_data(const std::vector<unsigned char>& bytes, const std::filesystem::path& path,
                      ColorEncoding encoding) {
  const Format format = check_before_decoding(path, bytes);
  if (format == Format::openexr) return load_exr(path, bytes);
  return load_stb(path, bytes, encoding);
}

ImageInfo probe_image_data(const std::vector<unsigned char>& bytes, const std::filesystem::path& path) {
  if (bytes.empty()) fail(path, "file is empty");
  const Format format = require_format(path, bytes);
  if (format == Format::png) check_png_chunks(path, bytes);
  return probe_bytes(path, bytes, format);
}

void save_exr_layers(const std::filesystem::path& path, const std::vector<ExrLayer>& layers) {
  if (lower_extension(path) != ".exr") fail(path, "layers can only be written to an .exr file");
  if (layers.empty() || !layers[0].image || layers[0].image->width <= 0 || layers[0].image->height <= 0)
    fail(path, "cannot save an empty or inconsistent image");
  const std::vector<unsigned char> file = encode_exr_layers(path, layers);
  try {
    write_file_atomically(path, file.data(), file.size());
  } catch (const FileWriteError& e) {
    fail(path, e.problem);
  }
}

Image load_exr_layer(const std::filesystem::path& path, const std::string& layer) {
  const std::vector<unsigned char> bytes = read_image_file(path);
  if (check_before_decoding(path, bytes) != Format::openexr) fail(path, "not an OpenEXR file");
  return load_exr(path, bytes, layer);
}

void save_image(const std::filesystem::path& path, const Image& image) {
  const std::string ext = lower_extension(path);
  if (ext != ".png" && ext != ".hdr" && ext != ".exr")
    fail(path, "unknown image extension '" + ext + "' (use .png, .hdr or .exr)");
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<size_t>(image.width) * image.height * 4)
    fail(path, "cannot save an empty or inconsistent image");
  const std::vector<unsigned char> file = ext == ".png"   ? encode_png(path, image)
                                          : ext == ".hdr" ? encode_hdr(path, image)
                                                          : encode_exr(path, image);
  try {
    write_file_atomically(path, file.data(), file.size());
  } catch (const FileWriteError& e) {
    fail(path, e.problem);
  }
}

ExrWithAttributes load_exr_with_attributes(const std::filesystem::path& path, const std::string& alpha_channel,
                                           const ExrHeaderCheck& before_decoding) {
  const std::vector<unsigned char> bytes = read_image_file(path);
  if (check_before_decoding(path, bytes) != Format::openexr) fail(path, "not an OpenEXR file");
  ExrWithAttributes result;
  result.image = load_exr(path, bytes, "", alpha_channel, &result.attributes, before_decoding);
  return result;
}

ExrHeaderInfo read_exr_header(const std::filesystem::path& path) {
  // As probe_image: a prefix, and the whole file only when the header does not fit in it.
  constexpr size_t kPrefix = 65536;
  std::vector<unsigned char> bytes = read_file(path, kPrefix);
  if (require_format(path, bytes) != Format::openexr) fail(path, "not an OpenEXR file");
  if (bytes.size() == kPrefix) {
    try {
      ExrFile exr;
      parse_exr_header(path, bytes, exr);
      return header_info(exr.header);
    } catch (const ImageError&) {
      bytes = read_image_file(path);
    }
  }
  ExrFile exr;
  parse_exr_header(path, bytes, exr);
  return header_info(exr.header);
}

void save_exr(const std::filesystem::path& path, const Image& image, const ExrAttributes& attributes,
              const std::string& alpha_channel) {
  if (lower_extension(path) != ".exr") fail(path, "an image with attributes must be an .exr file");
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<size_t>(image.width) * image.height * 4)
    fail(path, "cannot save an empty or inconsistent image");
  // With `alpha_channel`, the image's alpha goes to a channel of that name (sorted after R, as
  // OpenEXR requires, so a lowercase name) and A is 1.
  std::vector<ExrLayer> layers{{"", &image, "RGBA"}};
  Image opaque;
  if (!alpha_channel.empty()) {
    opaque = image;
    for (size_t i = 3; i < opaque.pixels.size(); i += 4) opaque.pixels[i] = 1.0f;
    layers = {{"", &opaque, "RGBA"}, {alpha_channel, &image, "", 3}};
  }
  const std::vector<unsigned char> file = encode_exr_layers(path, layers, attributes);
  try {
    write_file_atomically(path, file.data(), file.size());
  } catch (const FileWriteError& e) {
    fail(path, e.problem);
  }
}

}  // namespace glint
