// What the image readers and writers (image_io.cpp for PNG, JPEG and Radiance HDR through stb,
// exr_io.cpp for OpenEXR through tinyexr) share: the error they throw, the size limit, reading a
// file's bytes, telling the formats apart by signature and writing a file. Not part of image.h's
// public interface.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace glint {

// Larger images are refused before any pixel memory is allocated: a corrupt or hostile header
// must not make us allocate gigabytes.
constexpr int kMaxImageDimension = 16384;

// Throws ImageError "PATH: problem".
[[noreturn]] void image_fail(const std::filesystem::path& path, const std::string& problem);

// Refuses a size that is not positive or is over kMaxImageDimension on a side.
void check_image_dimensions(const std::filesystem::path& path, int width, int height);

// The extension in lower case (".exr").
std::string lower_extension(const std::filesystem::path& path);

// Up to `max_bytes` from the start of a regular file; refuses a missing, empty or unreadable
// file, a folder, a FIFO or a device.
std::vector<unsigned char> read_image_prefix(const std::filesystem::path& path, size_t max_bytes);

// The whole file for a decoder. stb takes an int length, so files of 2 GiB or more are refused
// up front.
std::vector<unsigned char> read_image_file(const std::filesystem::path& path);

enum class ImageFormat { png, jpeg, radiance, openexr };

// The format of image.h that the bytes' signature names, or an ImageError.
ImageFormat require_image_format(const std::filesystem::path& path, const std::vector<unsigned char>& bytes);

// CRC-32 of a PNG chunk's type and data (ISO 15948 annex D): png_crc(data, size, 0xffffffff) ^
// 0xffffffff, or continued over several spans.
uint32_t png_crc(const unsigned char* data, size_t size, uint32_t crc);

// stb_image checks neither the CRC of PNG chunks nor zlib's Adler-32, so a corrupted file can
// decode to wrong pixels without an error: refuses a PNG whose chunks run past the end or fail
// their CRC.
void check_png_chunks(const std::filesystem::path& path, const std::vector<unsigned char>& bytes);

// What every decoder needs first: a non-empty file that stb's int lengths can hold, of a known
// format, and for PNG intact chunks (check_png_chunks).
ImageFormat check_before_decoding(const std::filesystem::path& path, const std::vector<unsigned char>& bytes);

// Writes an encoded file atomically (write_file_atomically); a failure is an ImageError naming
// the file and the OS reason.
void write_image_file(const std::filesystem::path& path, const std::vector<unsigned char>& file);

}  // namespace glint
