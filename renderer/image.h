// Images in memory and on disk. Pixels are linear float RGBA unless stated; 8-bit sources can be
// decoded from sRGB on load. Readers: PNG (8/16-bit), JPG, HDR via stb; EXR via tinyexr.
// Writers: PNG (8-bit, from display values in [0,1]), HDR, EXR (float32).
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace glint {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> pixels;  // RGBA, row-major, first row is the top of the image

  float* at(int x, int y) { return &pixels[(static_cast<size_t>(y) * width + x) * 4]; }
  const float* at(int x, int y) const { return &pixels[(static_cast<size_t>(y) * width + x) * 4]; }
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

// Writes by extension: .png (values clamped to [0,1], written as 8-bit without further encoding),
// .hdr (RGB), .exr (RGBA float32), atomically (write_file_atomically, atomic_file.h). Throws
// ImageError naming the file and the OS reason on failure (the old file is then unchanged)
// or for an unknown extension.
void save_image(const std::filesystem::path& path, const Image& image);

float srgb_to_linear(float c);
float linear_to_srgb(float c);

}  // namespace glint
