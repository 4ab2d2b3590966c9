// Image readers and writers (see image.h) for PNG, JPEG and Radiance HDR through stb_image, and
// the format-independent entry points, which hand OpenEXR to exr_io.cpp. stb is linked as a
// shared object that already contains its implementation, so no *_IMPLEMENTATION macro is
// defined here.
#include "renderer/image.h"

#include "renderer/exr_io.h"
#include "renderer/image_file.h"
#include "renderer/image_metadata.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>

#include <stb_image.h>
#include <stb_image_write.h>

namespace glint {
namespace {

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
  if (source.overrun) image_fail(path, "file is truncated (incomplete image header)");
  if (!ok) image_fail(path, "not a readable image (" + stb_reason() + ")");
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
  if (source.overrun) image_fail(path, "file is truncated");
  if (!data) image_fail(path, "cannot decode image (" + stb_reason() + ")");
  check_image_dimensions(path, width, height);
  if (channels < 1 || channels > 4) image_fail(path, "unsupported channel count");
  return expand_to_rgba(data.get(), width, height, channels, convert);
}

Image load_stb(const std::filesystem::path& path, const std::vector<unsigned char>& bytes,
               ColorEncoding encoding) {
  const StbInfo info = stb_info(path, bytes);
  check_image_dimensions(path, info.width, info.height);
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
  if (source.overrun) image_fail(path, "file is truncated");
  if (!data) image_fail(path, "cannot decode image (" + stb_reason() + ")");
  check_image_dimensions(path, width, height);
  if (channels < 1 || channels > 4) image_fail(path, "unsupported channel count");
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
    image_fail(path, text);
  }
}

ImageInfo probe_bytes(const std::filesystem::path& path, const std::vector<unsigned char>& bytes,
                      ImageFormat format) {
  if (format == ImageFormat::openexr) return probe_exr(path, bytes);  // also checks the size
  const StbInfo stb = stb_info(path, bytes);
  check_image_dimensions(path, stb.width, stb.height);
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
    image_fail(path, "cannot encode the PNG image");
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
    image_fail(path, "cannot encode the Radiance HDR image");
  return file;
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
  std::vector<unsigned char> bytes = read_image_prefix(path, kPrefix);
  const ImageFormat format = require_image_format(path, bytes);
  if (format == ImageFormat::png) {
    // The whole file: its chunk CRCs are cheap to check and catch corruption anywhere, so a
    // project with a damaged texture is refused when it is opened, not when it is rendered.
    if (bytes.size() == kPrefix) bytes = read_image_prefix(path, std::numeric_limits<int>::max());
    check_png_chunks(path, bytes);
  }
  if (bytes.size() == kPrefix) {
    try {
      return probe_bytes(path, bytes, format);
    } catch (const ImageError&) {
      bytes = read_image_prefix(path, std::numeric_limits<int>::max());
    }
  }
  return probe_bytes(path, bytes, format);
}

Image load_image(const std::filesystem::path& path, ColorEncoding encoding) {
  return load_image_data(read_image_file(path), path, encoding);
}

TextureImage load_texture_image(const std::filesystem::path& path) {
  return load_texture_image_data(read_image_file(path), path);
}

TextureImage load_texture_image_data(const std::vector<unsigned char>& bytes,
                                     const std::filesystem::path& path) {
  const ImageFormat format = check_before_decoding(path, bytes);
  TextureImage texture;
  if (format != ImageFormat::openexr) {
    const StbInfo info = stb_info(path, bytes);
    check_image_dimensions(path, info.width, info.height);
    if (!info.is_hdr && !info.is_16_bit) return load_stb_rgba8(path, bytes);
    texture.linear = load_stb(path, bytes, ColorEncoding::linear);
  } else {
    texture.linear = decode_exr(path, bytes);
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
  const ImageFormat format = check_before_decoding(path, bytes);
  if (format == ImageFormat::openexr) return decode_exr(path, bytes);
  return load_stb(path, bytes, encoding);
}

ImageInfo probe_image_data(const std::vector<unsigned char>& bytes, const std::filesystem::path& path) {
  if (bytes.empty()) image_fail(path, "file is empty");
  const ImageFormat format = require_image_format(path, bytes);
  if (format == ImageFormat::png) check_png_chunks(path, bytes);
  return probe_bytes(path, bytes, format);
}

void save_image(const std::filesystem::path& path, const Image& image, const ImageMetadata& metadata) {
  const std::string ext = lower_extension(path);
  if (ext != ".png" && ext != ".hdr" && ext != ".exr")
    image_fail(path, "unknown image extension '" + ext + "' (use .png, .hdr or .exr)");
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<size_t>(image.width) * image.height * 4)
    image_fail(path, "cannot save an empty or inconsistent image");
  check_image_metadata(path, metadata);
  const std::vector<unsigned char> file = ext == ".png"   ? with_png_text(encode_png(path, image), metadata)
                                          : ext == ".hdr" ? with_hdr_header_lines(encode_hdr(path, image), metadata)
                                                          : encode_exr(path, image, metadata);
  write_image_file(path, file);
}

}  // namespace glint