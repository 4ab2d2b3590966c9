// Images in memory and on disk. Pixels are linear float RGBA unless stated; 8-bit sources can be
// decoded from sRGB on load. Readers: PNG (8/16-bit), JPG, HDR via stb; EXR via tinyexr.
// Writers: PNG (8-bit, from display values in [0,1]), HDR, EXR (float32).
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace glint {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> pixels;  // RGBA, row-major, first row is the top of the image

  float* at(int x, int y) { return &pixels[(static_cast<size_t>(y) * width + x) * 4]; }
  const float* at(int x, int y) const { return &pixels[(static_cast<size_t>(y) * width + x) * 4]; }

  // width x height pixels whose four channels all hold `value`.
  static Image filled(int width, int height, float value) {
    Image image;
    image.width = width;
    image.height = height;
    image.pixels.assign(static_cast<size_t>(width) * height * 4, value);
    return image;
  }
};

// Thrown by every reader and writer; what() names the file and the problem.
struct ImageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

enum class ColorEncoding {
  srgb,    // 8-bit values are sRGB-encoded: decode to linear (colour and emission textures)
  linear,  // 8-bit values are linear (roughness textures, data)
};

struct ImageInfo {
  int width = 0;
  int height = 0;
  int channels = 0;
  bool high_dynamic_range = false;  // HDR/EXR/16-bit: already linear, never sRGB-decoded
};

// Reads the header only; throws ImageError if the file is missing, unreadable or not an image.
ImageInfo probe_image(const std::filesystem::path& path);

// Reads the whole image as linear RGBA float. Grey becomes (g, g, g, 1), missing alpha is 1.
// `encoding` applies only to 8-bit sources.
Image load_image(const std::filesystem::path& path, ColorEncoding encoding);

// The same for a file's bytes already in memory (the fuzz targets); `label` names it in errors.
ImageInfo probe_image_data(const std::vector<unsigned char>& bytes, const std::filesystem::path& label);
Image load_image_data(const std::vector<unsigned char>& bytes, const std::filesystem::path& label,
                      ColorEncoding encoding);

// A texture as the renderer keeps it, in memory and on the GPU. 8-bit sources stay 8-bit:
// `rgba8` holds their RGBA values as stored in the file (sRGB not decoded: the shader decodes
// each tap, so one copy serves a texture used both as colour and as data), 4 bytes a texel.
// 16-bit, HDR and EXR sources are linear RGBA float in `linear`, 16 bytes a texel. `linear`'s
// width and height are set in both cases. Every float texel is finite and non-negative.
struct TextureImage {
  Image linear;
  std::vector<unsigned char> rgba8;

  bool eight_bit() const { return linear.pixels.empty(); }
  int width() const { return linear.width; }
  int height() const { return linear.height; }
  size_t byte_size() const { return rgba8.size() + linear.pixels.size() * sizeof(float); }
  // Channel c of texel (x, y) as load_image would give it with `encoding`.
  float value(int x, int y, int c, ColorEncoding encoding) const;
};

// Reads a texture or environment file. Throws ImageError naming the file for everything
// load_image refuses and for a texel that is not finite or is negative (NaN, Inf, -5 in an
// HDR or EXR file), naming the first such texel (x, y, channel).
TextureImage load_texture_image(const std::filesystem::path& path);
TextureImage load_texture_image_data(const std::vector<unsigned char>& bytes,
                                     const std::filesystem::path& label);

// The same texels as linear RGBA float (a copy), as load_image(path, encoding) reads them.
Image to_linear_image(const TextureImage& texture, ColorEncoding encoding);

// Writes by extension: .png (values clamped to [0,1], written as 8-bit without further encoding),
// .hdr (RGB), .exr (RGBA float32), atomically (write_file_atomically, atomic_file.h). Throws
// ImageError naming the file and the OS reason on failure (the old file is then unchanged)
// or for an unknown extension. `metadata`: text entries the file carries (PNG text chunks, Radiance
// header lines, OpenEXR string attributes: renderer/image_metadata.h), each checked first
// (check_image_metadata): an entry that breaks the rules is an ImageError and nothing is written.
using ImageMetadata = std::vector<std::pair<std::string, std::string>>;
void save_image(const std::filesystem::path& path, const Image& image, const ImageMetadata& metadata = {});

// The rule for a render's output (`glint render`, `merge`, `farm`, a farm plan, the editor's
// export): its name ends in .png, .hdr or .exr, as typed. nullopt when it does, else
// "must end in .png, .hdr or .exr" (the caller names the file or field before it).
inline std::optional<std::string> output_format_problem(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".png" || ext == ".hdr" || ext == ".exr") return std::nullopt;
  return "must end in .png, .hdr or .exr";
}

// String attributes of an OpenEXR header, (name, value) in file order: a render part's
// provenance (renderer/render_part.h).
using ExrAttributes = std::vector<std::pair<std::string, std::string>>;

// Writes an .exr like save_image (atomically), with `attributes` in the header. With
// `alpha_channel` (a lowercase name), the image's alpha is written as a channel of that name
// and A is 1.
void save_exr(const std::filesystem::path& path, const Image& image, const ExrAttributes& attributes,
              const std::string& alpha_channel = "");

// Reads an .exr and its string attributes; with `alpha_channel`, alpha is that channel (a file
// without it is refused). Throws ImageError naming the file.
struct ExrWithAttributes {
  Image image;
  ExrAttributes attributes;
};
// An OpenEXR file's header, read without its pixels: the data window, the channels and the
// string attributes.
enum class ExrPixelType { uint32, half, float32 };
struct ExrChannel {
  std::string name;
  ExrPixelType type = ExrPixelType::float32;
};
struct ExrHeaderInfo {
  int min_x = 0, min_y = 0;  // the data window's first pixel
  int width = 0, height = 0;  // the data window's size (each within the reader's 16384 a side)
  std::vector<ExrChannel> channels;
  ExrAttributes attributes;
};
// Reads and parses the header alone (the start of the file; all of it only for a header longer
// than 64 KiB). Throws ImageError naming the file.
ExrHeaderInfo read_exr_header(const std::filesystem::path& path);
// Called with the header of the file being read before any of its pixels is decoded: it
// throws to refuse the file.
using ExrHeaderCheck = std::function<void(const ExrHeaderInfo&)>;
ExrWithAttributes load_exr_with_attributes(const std::filesystem::path& path,
                                           const std::string& alpha_channel = "",
                                           const ExrHeaderCheck& before_decoding = nullptr);
// One layer of a multi-layer OpenEXR file: channel "<name>.<letter>" for each letter of
// `channels` takes the image's RGBA components in order (the unnamed layer "" gives plain R, G,
// B, A, which every viewer shows). E.g. {"albedo", &a, "RGB"}, {"N", &n, "XYZ"}.
struct ExrLayer {
  std::string name;
  const Image* image = nullptr;
  std::string channels = "RGBA";
  // >= 0: the layer is the one channel named `name` (no letters added), taking this component.
  int single_component = -1;
};
// Writes the layers (all of one size) as float32 channels, atomically, with `metadata` as
// string attributes (as save_image). Throws ImageError.
void save_exr_layers(const std::filesystem::path& path, const std::vector<ExrLayer>& layers,
                     const ImageMetadata& metadata = {});
// Reads one named layer of an OpenEXR file (layer.R/G/B or layer.X/Y/Z, layer.A if present,
// else alpha 1). Throws ImageError naming the file, also when the layer is missing.
Image load_exr_layer(const std::filesystem::path& path, const std::string& layer);

float srgb_to_linear(float c);
float linear_to_srgb(float c);

}  // namespace glint
