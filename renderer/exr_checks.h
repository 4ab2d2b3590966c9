// Checks of OpenEXR bytes that tinyexr 1.0.1 (Debian 12's) reads without checking them against
// the file's size, made before tinyexr parses or decodes them (exr_io.cpp). Each returns what
// is wrong, or "" when it found nothing wrong; bytes it cannot walk are left to tinyexr, whose
// own checks report them. All of these were found by the fuzzer (tests/fuzz/fuzz_image.cpp),
// and its inputs are in tests/fuzz/corpus/image.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace glint {

// tinyexr reads a "tiles" attribute as 9 bytes whatever size the file gives it. Walks the
// single-part header's attributes (name, type, 32-bit little-endian size, data).
std::string unsafe_exr_attribute(const std::vector<unsigned char>& bytes);

// tinyexr sizes its offset table (8 bytes an entry) from the header before reading it: from a
// chunkCount attribute, or in a tiled file from the tile size (1x1 tiles of a 16384x16384 image
// make 2^28 entries, 2 GiB). A table of `entries` that cannot fit in the file after
// `table_start` is refused before tinyexr allocates it.
std::string unsafe_offset_table(size_t file_size, size_t table_start, unsigned long long entries);

// The offset table entries of level 0 of a tiled image (tinyexr adds the other levels of a
// mipmap or ripmap), or 0 for tile sizes below 1.
unsigned long long level0_tiles(int width, int height, int tile_width, int tile_height);

// What locates and sizes the blocks of a single-part scanline file, from its parsed header.
struct ExrScanlineLayout {
  size_t table_start = 0;  // the offset table's first byte: 8 + tinyexr's header_len
  int blocks = 0;          // entries in the table
  int min_y = 0;           // the data window's first line
  int width = 0, height = 0;
  int lines_per_block = 32;  // PIZ's
  int bytes_per_pixel = 0;   // over all channels: 2 for each half, 4 for each float or uint
};

// tinyexr decodes a PIZ block without checking its parts against the block's size: the bitmap
// range (minNonZero..maxNonZero) is copied, and the Huffman data's 20-byte header read, past the
// block's end. Checks every entry of the offset table (a whole block inside the file, on a line
// of the data window) and, in each block that is not stored uncompressed, the bitmap range and
// the Huffman data's length.
std::string unsafe_piz_blocks(const std::vector<unsigned char>& bytes, const ExrScanlineLayout& layout);

// Zero bytes to add after a PIZ file's bytes before tinyexr decodes them: its Huffman table
// reader may look one byte past the table (an off-by-one in hufUnpackEncTable), which then
// stays inside memory we own.
constexpr size_t kPizReadPadding = 16;

}  // namespace glint
