// Reading OpenEXR through tinyexr (see exr_io.h; exr_write.cpp writes). tinyexr is linked as a
// shared object that already contains its implementation, so TINYEXR_IMPLEMENTATION is not
// defined here.
#include "renderer/exr_io.h"

#include "renderer/exr_checks.h"
#include "renderer/image_file.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>
#include <utility>

#include <sys/mman.h>

#include <tinyexr.h>

namespace glint {
namespace {

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

// What a read asks for besides the pixels (load_exr_layer, load_exr_with_attributes).
struct ExrReadRequest {
  std::string layer;          // "": the unnamed layer (R, G, B, A or a grey channel)
  std::string alpha_channel;  // a channel read as alpha instead of A, and then required
  ExrAttributes* attributes = nullptr;  // receives the header's string attributes
  ExrHeaderCheck before_decoding;       // called with the header before any pixel is decoded
};

// The channel that feeds R, G, B and A, or -1 (A is then 1).
using RgbaChannels = std::array<int, 4>;

// The data window's size once parse_exr_header has checked it.
int window_width(const EXRHeader& header) { return header.data_window.max_x - header.data_window.min_x + 1; }
int window_height(const EXRHeader& header) { return header.data_window.max_y - header.data_window.min_y + 1; }

void parse_exr_header(const std::filesystem::path& path, const std::vector<unsigned char>& bytes,
                      ExrFile& exr) {
  int ret = ParseEXRVersionFromMemory(&exr.version, bytes.data(), bytes.size());
  if (ret != TINYEXR_SUCCESS) image_fail(path, "not a readable OpenEXR file (bad version field)");
  if (exr.version.multipart || exr.version.non_image)
    image_fail(path, "multi-part and deep OpenEXR files are not supported");
  if (const std::string unsafe = unsafe_exr_attribute(bytes); !unsafe.empty())
    image_fail(path, "bad OpenEXR header (" + unsafe + ")");
  const char* err = nullptr;
  ret = ParseEXRHeaderFromMemory(&exr.header, &exr.version, bytes.data(), bytes.size(), &err);
  if (ret != TINYEXR_SUCCESS) image_fail(path, "bad OpenEXR header (" + take_exr_error(err, ret) + ")");
  const EXRBox2i& box = exr.header.data_window;
  // 64-bit arithmetic: the window corners come straight from the file.
  const long long w = static_cast<long long>(box.max_x) - box.min_x + 1;
  const long long h = static_cast<long long>(box.max_y) - box.min_y + 1;
  check_image_dimensions(path, static_cast<int>(std::clamp<long long>(w, -1, kMaxImageDimension + 1)),
                         static_cast<int>(std::clamp<long long>(h, -1, kMaxImageDimension + 1)));
}

ExrPixelType pixel_type(int tinyexr_type) {
  return tinyexr_type == TINYEXR_PIXELTYPE_HALF    ? ExrPixelType::half
         : tinyexr_type == TINYEXR_PIXELTYPE_FLOAT ? ExrPixelType::float32
                                                   : ExrPixelType::uint32;
}

// A header that parse_exr_header accepted, as image.h describes it.
ExrHeaderInfo header_info(const EXRHeader& header) {
  ExrHeaderInfo info;
  info.min_x = header.data_window.min_x;
  info.min_y = header.data_window.min_y;
  info.width = window_width(header);
  info.height = window_height(header);
  for (int c = 0; c < header.num_channels; ++c)
    info.channels.push_back({header.channels[c].name, pixel_type(header.pixel_types[c])});
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

ExrHeaderInfo parse_header_info(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
  ExrFile exr;
  parse_exr_header(path, bytes, exr);
  return header_info(exr.header);
}

// Hands the header to the request's check and attributes, before any pixel is decoded.
void report_header(const EXRHeader& header, const ExrReadRequest& request) {
  if (!request.attributes && !request.before_decoding) return;
  ExrHeaderInfo info = header_info(header);
  if (request.before_decoding) request.before_decoding(info);
  if (request.attributes) *request.attributes = std::move(info.attributes);
}

// Every channel is read as float, whole: sub-sampled channels are refused, and so are UINT
// ones, which tinyexr cannot convert.
void request_float_channels(const std::filesystem::path& path, EXRHeader& header) {
  for (int c = 0; c < header.num_channels; ++c) {
    const EXRChannelInfo& channel = header.channels[c];
    if (channel.x_sampling != 1 || channel.y_sampling != 1)
      image_fail(path, "sub-sampled OpenEXR channels are not supported");
    if (header.pixel_types[c] == TINYEXR_PIXELTYPE_HALF)
      header.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
    else if (header.pixel_types[c] == TINYEXR_PIXELTYPE_UINT)
      image_fail(path, "integer OpenEXR channel '" + std::string(channel.name) + "' is not supported");
  }
}

// Which of R, G, B (0 to 2) channel `name` feeds in the layer of `prefix` ("" or "layer."), or
// -1; a named layer may use X, Y, Z instead.
int colour_slot(const std::string& name, const std::string& prefix, bool named_layer) {
  static const char* const kLetters[2][3] = {{"R", "G", "B"}, {"X", "Y", "Z"}};
  for (int slot = 0; slot < 3; ++slot)
    if (name == prefix + kLetters[0][slot] || (named_layer && name == prefix + kLetters[1][slot])) return slot;
  return -1;
}

// The channels the request reads: layer.R/G/B (or layer.X/Y/Z) and layer.A, or the request's
// alpha channel; without a layer, R/G/B or else one grey channel (Y, or a single channel of any
// name) for all three.
RgbaChannels find_rgba_channels(const std::filesystem::path& path, const EXRHeader& header,
                                const ExrReadRequest& request) {
  const std::string& layer = request.layer;
  const std::string prefix = layer.empty() ? "" : layer + ".";
  const std::string alpha = request.alpha_channel.empty() ? prefix + "A" : request.alpha_channel;
  RgbaChannels index = {-1, -1, -1, -1};
  int luminance = -1;
  for (int c = 0; c < header.num_channels; ++c) {
    const std::string name = header.channels[c].name;
    if (const int slot = colour_slot(name, prefix, !layer.empty()); slot >= 0) index[slot] = c;
    if (name == alpha) index[3] = c;
    if (layer.empty() && name == "Y") luminance = c;
  }
  if (!request.alpha_channel.empty() && index[3] < 0)
    image_fail(path, "OpenEXR file has no '" + request.alpha_channel + "' channel");
  if (index[0] >= 0 && index[1] >= 0 && index[2] >= 0) return index;
  if (!layer.empty())
    image_fail(path, "OpenEXR file has no layer '" + layer + "' (channels " + prefix + "R/G/B or X/Y/Z)");
  if (header.num_channels == 1 && luminance < 0) luminance = 0;
  if (luminance < 0) image_fail(path, "OpenEXR file has neither R, G, B nor a single grey channel");
  index[0] = index[1] = index[2] = luminance;
  return index;
}

// tinyexr allocates the offset table that the header implies before reading it: a table that
// the file cannot hold is refused first (exr_checks.h). Returns where the table starts.
size_t check_offset_table(const std::filesystem::path& path, const std::vector<unsigned char>& bytes,
                          const EXRHeader& header) {
  const size_t table_start = 8 + size_t(header.header_len);
  unsigned long long entries = 0;  // 0: the table follows from the height alone (small)
  if (header.tiled) {
    entries = level0_tiles(window_width(header), window_height(header), header.tile_size_x, header.tile_size_y);
    if (entries == 0)
      image_fail(path, "bad OpenEXR header (tile size " + std::to_string(header.tile_size_x) + "x" +
                           std::to_string(header.tile_size_y) + ")");
  } else if (header.chunk_count > 0) {
    entries = static_cast<unsigned long long>(header.chunk_count);
  }
  if (const std::string unsafe = unsafe_offset_table(bytes.size(), table_start, entries); !unsafe.empty())
    image_fail(path, "bad OpenEXR header (" + unsafe + ")");
  return table_start;
}

// tinyexr's PIZ decoder reads past a malformed block (exr_checks.h): the blocks of a PIZ file
// are checked, and it is decoded from a copy with padding, which this returns (empty for the
// other compressions, decoded from the bytes themselves).
std::vector<unsigned char> checked_piz_copy(const std::filesystem::path& path, const std::vector<unsigned char>& bytes,
                                            const EXRHeader& header, size_t table_start) {
  if (header.compression_type != TINYEXR_COMPRESSIONTYPE_PIZ) return {};
  if (header.tiled) image_fail(path, "tiled PIZ-compressed OpenEXR files are not supported");
  ExrScanlineLayout layout;
  layout.table_start = table_start;
  layout.min_y = header.data_window.min_y;
  layout.width = window_width(header);
  layout.height = window_height(header);
  layout.blocks = header.chunk_count > 0 ? header.chunk_count
                                         : (layout.height + layout.lines_per_block - 1) / layout.lines_per_block;
  for (int c = 0; c < header.num_channels; ++c)
    layout.bytes_per_pixel += header.pixel_types[c] == TINYEXR_PIXELTYPE_HALF ? 2 : 4;
  if (const std::string unsafe = unsafe_piz_blocks(bytes, layout); !unsafe.empty())
    image_fail(path, "corrupt OpenEXR data (" + unsafe + ")");
  std::vector<unsigned char> padded = bytes;
  padded.resize(bytes.size() + kPizReadPadding, 0);
  return padded;
}

std::string pixel_count_text(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height) + " pixels";
}

// tinyexr allocates each channel's pixels with malloc and does not check the result: where the
// memory is not there (under an address-space limit) it writes through a null pointer. The
// same blocks are mapped, all at once, and unmapped first, so that a shortage is an error
// naming the file. (Large blocks are what malloc maps this way too.)
void check_decode_memory(const std::filesystem::path& path, const EXRHeader& header) {
  const int width = window_width(header), height = window_height(header);
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
    image_fail(path, "not enough memory to decode its " + pixel_count_text(width, height) + " (" +
                         std::to_string(total >> 20) + " MiB for " + std::to_string(header.num_channels) +
                         " channels)");
}

// Decodes the pixels of a checked header from `data` (the file's `size` bytes, perhaps padded).
void decode_exr_pixels(const std::filesystem::path& path, const unsigned char* data, size_t size, ExrFile& exr) {
  // tinyexr frees a half-decoded image itself when decoding fails, but only the channels that
  // exr.image.num_channels counts, which it sets on success: preset it so that nothing leaks.
  exr.image.num_channels = exr.header.num_channels;
  check_decode_memory(path, exr.header);
  const char* err = nullptr;
  int ret = TINYEXR_ERROR_INVALID_DATA;
  try {
    ret = LoadEXRImageFromMemory(&exr.image, &exr.header, data, size, &err);
  } catch (const std::bad_alloc&) {
    exr.image_loaded = true;  // frees the channels it allocated
    image_fail(path, "not enough memory to decode its " +
                         pixel_count_text(window_width(exr.header), window_height(exr.header)));
  }
  if (ret != TINYEXR_SUCCESS) image_fail(path, "cannot decode OpenEXR data (" + take_exr_error(err, ret) + ")");
  exr.image_loaded = true;
}

// Copies one block of rows or one tile into `image`: `channels[c]` holds block_w x block_h floats.
void copy_block(Image& image, const RgbaChannels& rgba, unsigned char* const* channels, int x0, int y0,
                int block_w, int block_h) {
  for (int y = 0; y < block_h && y0 + y < image.height; ++y)
    for (int x = 0; x < block_w && x0 + x < image.width; ++x) {
      float* out = image.at(x0 + x, y0 + y);
      const size_t src = static_cast<size_t>(y) * block_w + x;
      for (int c = 0; c < 4; ++c)
        if (rgba[c] >= 0) out[c] = reinterpret_cast<const float*>(channels[rgba[c]])[src];
    }
}

// The decoded channels as RGBA (a channel that `rgba` leaves out is 1).
Image copy_exr_pixels(const std::filesystem::path& path, const ExrFile& exr, const RgbaChannels& rgba) {
  Image image;
  image.width = exr.image.width;
  image.height = exr.image.height;
  check_image_dimensions(path, image.width, image.height);
  image.pixels.assign(static_cast<size_t>(image.width) * image.height * 4, 1.0f);
  const EXRHeader& header = exr.header;
  if (header.tiled) {
    if (!exr.image.tiles) image_fail(path, "OpenEXR file has no tiles");
    for (int t = 0; t < exr.image.num_tiles; ++t) {
      const EXRTile& tile = exr.image.tiles[t];
      // The tile buffers are tile_size_x wide even when the tile is clipped at the border.
      copy_block(image, rgba, tile.images, tile.offset_x * header.tile_size_x, tile.offset_y * header.tile_size_y,
                 header.tile_size_x, std::min(tile.height, header.tile_size_y));
    }
  } else {
    if (!exr.image.images) image_fail(path, "OpenEXR file has no pixel data");
    copy_block(image, rgba, exr.image.images, 0, 0, image.width, image.height);
  }
  return image;
}

// The header is parsed and checked, handed to the request, its channels chosen, its offset
// table (and PIZ blocks) checked against the file, and only then are the pixels decoded.
Image read_exr(const std::filesystem::path& path, const std::vector<unsigned char>& bytes,
               const ExrReadRequest& request) {
  ExrFile exr;
  parse_exr_header(path, bytes, exr);
  report_header(exr.header, request);
  request_float_channels(path, exr.header);
  const RgbaChannels rgba = find_rgba_channels(path, exr.header, request);
  const size_t table_start = check_offset_table(path, bytes, exr.header);
  const std::vector<unsigned char> padded = checked_piz_copy(path, bytes, exr.header, table_start);
  decode_exr_pixels(path, padded.empty() ? bytes.data() : padded.data(), bytes.size(), exr);
  return copy_exr_pixels(path, exr, rgba);
}

// The whole of an OpenEXR file, checked as every decoder checks a file first.
std::vector<unsigned char> read_exr_file(const std::filesystem::path& path) {
  std::vector<unsigned char> bytes = read_image_file(path);
  if (check_before_decoding(path, bytes) != ImageFormat::openexr) image_fail(path, "not an OpenEXR file");
  return bytes;
}

}  // namespace

std::string take_exr_error(const char* err, int code) {
  std::string message = err ? err : "error code " + std::to_string(code);
  if (err) FreeEXRErrorMessage(err);
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  return message;
}

ImageInfo probe_exr(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
  ExrFile exr;
  parse_exr_header(path, bytes, exr);  // also checks the size
  return {window_width(exr.header), window_height(exr.header), exr.header.num_channels, true};
}

Image decode_exr(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
  return read_exr(path, bytes, {});
}

Image load_exr_layer(const std::filesystem::path& path, const std::string& layer) {
  ExrReadRequest request;
  request.layer = layer;
  return read_exr(path, read_exr_file(path), request);
}

ExrWithAttributes load_exr_with_attributes(const std::filesystem::path& path, const std::string& alpha_channel,
                                           const ExrHeaderCheck& before_decoding) {
  ExrWithAttributes result;
  ExrReadRequest request;
  request.alpha_channel = alpha_channel;
  request.attributes = &result.attributes;
  request.before_decoding = before_decoding;
  result.image = read_exr(path, read_exr_file(path), request);
  return result;
}

ExrHeaderInfo read_exr_header(const std::filesystem::path& path) {
  // As probe_image: a prefix, and the whole file only when the header does not fit in it.
  constexpr size_t kPrefix = 65536;
  std::vector<unsigned char> bytes = read_image_prefix(path, kPrefix);
  if (require_image_format(path, bytes) != ImageFormat::openexr) image_fail(path, "not an OpenEXR file");
  if (bytes.size() == kPrefix) {
    try {
      return parse_header_info(path, bytes);
    } catch (const ImageError&) {
      bytes = read_image_file(path);
    }
  }
  return parse_header_info(path, bytes);
}

}  // namespace glint
