// Text metadata of the images Glint writes: (key, value) pairs such as ("Software", "Glint 0.1
// (42cfb04d0e1a)") and ("glint.digest", ...), as Blender and pbrt record theirs. A PNG holds
// each as a text chunk (tEXt, or iTXt for a value beyond ASCII) after its header, a Radiance
// .hdr as a "KEY=VALUE" line of its header, an OpenEXR as a string attribute (image.h).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "renderer/image.h"  // ImageMetadata

namespace glint {

// The rules both writers hold every entry to: empty when the entry keeps them, else why not. A key is 1 to 79 printable ASCII characters without '=' or a leading, trailing or double
// space (PNG's keyword rule, and a Radiance variable name); a value has no NUL, CR or newline.
std::string metadata_entry_problem(const std::string& key, const std::string& value);
// Throws ImageError "PATH: metadata 'KEY': why" for the first entry that breaks them.
void check_image_metadata(const std::filesystem::path& path, const ImageMetadata& metadata);

// A PNG file's bytes with one text chunk per entry inserted after IHDR. Throws
// std::invalid_argument for an entry that breaks the rules above or a buffer that is not a PNG
// beginning with IHDR (what stb_image_write writes).
std::vector<unsigned char> with_png_text(const std::vector<unsigned char>& png, const ImageMetadata& metadata);

// A Radiance file's bytes with a "KEY=VALUE" line per entry after its first ("#?RADIANCE")
// line. Throws std::invalid_argument as above.
std::vector<unsigned char> with_hdr_header_lines(const std::vector<unsigned char>& hdr,
                                                 const ImageMetadata& metadata);

// Reads the metadata back, validating the bytes as untrusted input; `label` names the file in
// errors (ImageError, image.h). PNG: every tEXt and uncompressed iTXt chunk, in file order
// (compressed text is skipped). Radiance: every "KEY=VALUE" line of the header, FORMAT
// included. OpenEXR: the string attributes.
ImageMetadata read_png_text(const std::vector<unsigned char>& png, const std::filesystem::path& label);
ImageMetadata read_hdr_header_lines(const std::vector<unsigned char>& hdr, const std::filesystem::path& label);
ImageMetadata read_image_metadata(const std::filesystem::path& path);

}  // namespace glint
