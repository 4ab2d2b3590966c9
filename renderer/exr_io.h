// OpenEXR through tinyexr: the reader (exr_io.cpp) and writer (exr_write.cpp) that image.h's
// format-independent functions (probe_image, load_image, load_texture_image, save_image in
// image_io.cpp) hand an .exr to. The OpenEXR-only functions of image.h are defined there too:
// load_exr_layer, load_exr_with_attributes and read_exr_header in exr_io.cpp, save_exr and
// save_exr_layers in exr_write.cpp. The reader checks a forged, truncated or oversized file
// (with exr_checks.h) before tinyexr allocates or decodes anything.
#pragma once

#include "renderer/image.h"

#include <filesystem>
#include <string>
#include <vector>

namespace glint {

// The size and channel count from the header of an OpenEXR file's bytes (which may be only the
// start of the file). Throws ImageError naming `path`.
ImageInfo probe_exr(const std::filesystem::path& path, const std::vector<unsigned char>& bytes);

// The unnamed layer (R, G, B, A or a single grey channel) as linear RGBA float. Throws
// ImageError naming `path`.
Image decode_exr(const std::filesystem::path& path, const std::vector<unsigned char>& bytes);

// tinyexr's error message `err` (freed here), without its trailing newline, or the error code.
std::string take_exr_error(const char* err, int code);

// RGBA float32, ZIP compressed unless the image is smaller than 16x16, with `attributes` as
// string attributes. Throws ImageError.
std::vector<unsigned char> encode_exr(const std::filesystem::path& path, const Image& image,
                                      const ExrAttributes& attributes = {});

}  // namespace glint
