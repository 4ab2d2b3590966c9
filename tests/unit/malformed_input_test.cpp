// Malformed input, one row per case, each with the exact message it must produce: projects
// (truncated JSON, wrong types, unknown keys, NaN and infinities, sizes, limits, missing and
// broken textures, invalid UTF-8) and images (PNG, HDR and EXR written by the project's own
// writer, then cut or corrupted). Bad input is an error naming the file, the JSON path and the
// problem: never a crash, never a half-loaded scene (load_project returns whole scenes only).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <string>
#include <tuple>
#include <vector>

#include "renderer/image.h"
#include "renderer/project_file.h"
#include "renderer/scene_validation.h"
#include "tests/image_fixtures.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

using test::TempDir;

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
}

// A small image with values above 1 (for HDR and EXR) and partial alpha.
Image pattern(int w, int h) {
  Image image{w, h, std::vector<float>(static_cast<size_t>(w) * h * 4)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = image.at(x, y);
      p[0] = 0.1f + 0.03f * x;
      p[1] = 0.2f + 0.05f * y;
      p[2] = 2.5f * ((x + y) % 3);
      p[3] = 0.5f + 0.5f * (x % 2);
    }
  return image;
}

// A valid project using a PNG texture and an HDR environment, both in the project's folder.
const std::string kValid = R"({"format": "glint-project", "version": 1,
  "film": {"width": 64, "height": 32},
  "environment": {"texture": "sky.hdr"},
  "textures": [{"name": "wood", "path": "wood.png"}],
  "materials": [{"name": "m", "color_texture": "wood"}],
  "spheres": [{"name": "ball", "center": [0, 0.5, 0], "radius": 0.5, "material": "m"}]})";

// Replaces the one occurrence of `from` in kValid.
std::string edit(const std::string& from, const std::string& to) {
  const size_t at = kValid.find(from);
  if (at == std::string::npos || kValid.find(from, at + 1) != std::string::npos)
    throw std::logic_error("edit: not exactly one '" + from + "' in kValid");
  return kValid.substr(0, at) + to + kValid.substr(at + from.size());
}

// Each byte of `text` widened to two (its UTF-16 code unit, for ASCII text).
std::string utf16(const std::string& text, bool big_endian) {
  std::string out;
  for (char c : text) out += big_endian ? std::string{'\0', c} : std::string{c, '\0'};
  return out;
}

struct ProjectRow {
  const char* what;
  std::function<std::string()> text;  // the project file's content
  std::string message;                // exactly what() after "FILE: "; {dir} is the folder
};

std::string replace_dir(std::string message, const fs::path& dir) {
  for (size_t at; (at = message.find("{dir}")) != std::string::npos;)
    message.replace(at, 5, dir.string());
  return message;
}

void write_assets(const fs::path& dir) {
  save_image(dir / "wood.png", pattern(8, 8));
  save_image(dir / "sky.hdr", pattern(16, 8));
  save_image(dir / "sky.exr", pattern(16, 8));
  // Broken copies: cut in half, and one byte flipped in the middle of the pixel data.
  for (const char* name : {"wood.png", "sky.hdr", "sky.exr"}) {
    const std::string bytes = read_bytes(dir / name);
    write_bytes(dir / (std::string("cut-") + name), bytes.substr(0, bytes.size() / 2));
  }
  std::string png = read_bytes(dir / "wood.png");
  png[png.size() / 2] ^= 0x20;
  write_bytes(dir / "flip-wood.png", png);
  // Whole headers and chunks, so that they pass the probe: only decoding finds the problems.
  test::write_png_with_short_idat(dir / "short-idat.png");
  test::write_exr_without_rgb(dir / "no-rgb.exr", pattern(4, 4));
  // An offset table entry far past the end (the table follows the header, whose last attribute
  // is screenWindowWidth, a float).
  std::string exr = read_bytes(dir / "sky.exr");
  exr.at(exr.find(std::string("screenWindowWidth\0float\0", 24)) + 24 + 4 + 4 + 1 + 3) = '\x7f';
  write_bytes(dir / "far-offset.exr", exr);
  // Texels no light or colour can have, at (3, 2) green, (0, 0) red, (1, 3) alpha; a texel of
  // 1e30 (blue at (2, 1)), finite but too bright with an intensity of 1e10.
  for (const auto& [name, x, y, c, value] :
       {std::tuple{"nan.exr", 3, 2, 1, std::nanf("")}, std::tuple{"negative.exr", 0, 0, 0, -5.0f},
        std::tuple{"inf.exr", 1, 3, 3, INFINITY}, std::tuple{"bright.exr", 2, 1, 2, 1e30f}}) {
    Image image = pattern(4, 4);
    image.at(x, y)[c] = value;
    save_image(dir / name, image);
  }
  // Decompression bombs: headers of huge images over a few bytes of data.
  test::write_png_claiming(dir / "bomb.png", 16384, 16384);
  write_bytes(dir / "bomb.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 16384\n" + std::string(64, '\x7f'));
}

TEST(MalformedInput, ProjectsFailWithFileJsonPathAndProblem) {
  TempDir tmp;
  const fs::path& dir = tmp.path();
  write_assets(dir);
  const std::string huge_list = [] {  // one element over the limit, each the cheapest JSON
    std::string list = "[0";
    for (size_t i = 1; i <= kMaxSpheres; ++i) list += ",0";
    return list + "]";
  }();
  const std::vector<ProjectRow> rows = {
      // Not JSON, or not whole.
      {"empty file", [] { return std::string(); },
       "invalid JSON: parse error at line 1, column 1: syntax error while parsing value - "
       "unexpected end of input; expected '[', '{', or a literal"},
      {"truncated JSON", [] { return kValid.substr(0, 60); },
       "invalid JSON: parse error at line 2, column 19: syntax error while parsing object "
       "separator - unexpected end of input; expected ':'"},
      {"bare NaN", [] { return edit("\"radius\": 0.5", "\"radius\": NaN"); },
       "invalid JSON: parse error at line 6, column 65: syntax error while parsing value - "
       "invalid literal; last read: '\"radius\": N'"},
      {"raw byte 0xFF in a string", [] { return edit("\"ball\"", "\"b\xff\""); },
       "invalid JSON: parse error at line 6, column 26: syntax error while parsing value - "
       "invalid string: ill-formed UTF-8 byte; last read: '\"b\xff'"},
      {"lone UTF-16 surrogate", [] { return edit("\"ball\"", "\"\\udc80\""); },
       "invalid JSON: parse error at line 6, column 30: syntax error while parsing value - "
       "invalid string: surrogate U+DC00..U+DFFF must follow U+D800..U+DBFF; last read: "
       "'\"\\udc80'"},
      {"duplicate key", [] { return edit("\"radius\": 0.5", "\"radius\": 0.5, \"radius\": 2"); },
       "spheres[0].radius: duplicate key"},
      // Wrong types and unknown keys.
      {"not an object", [] { return std::string("[1, 2]"); },
       "expected a JSON object, got an array of 2"},
      {"number as string", [] { return edit("\"radius\": 0.5", "\"radius\": \"0.5\""); },
       "spheres[0].radius: expected a number, got string \"0.5\""},
      {"float film size", [] { return edit("\"width\": 64", "\"width\": 64.5"); },
       "film.width: expected an integer, got number 64.5"},
      {"object for a list", [] { return edit("\"spheres\": [", "\"spheres\": {\"a\": ["); },
       "invalid JSON: parse error at line 6, column 94: syntax error while parsing object - "
       "unexpected end of input; expected '}'"},
      {"list of the wrong thing", [] { return edit("\"textures\": [{", "\"textures\": [5, {"); },
       "textures[0]: expected an object, got number 5"},
      {"unknown top-level key", [] { return edit("\"film\"", "\"flim\""); },
       "flim: unknown key (expected one of: format, version, camera, film, render, display, "
       "environment, textures, materials, spheres, quads, views)"},
      {"unknown nested key", [] { return edit("\"radius\"", "\"raduis\""); },
       "spheres[0].raduis: unknown key (expected one of: name, center, radius, material)"},
      // NaN and infinities: as strings (JSON has neither), or as literals beyond a double.
      {"NaN as a string", [] { return edit("\"radius\": 0.5", "\"radius\": \"NaN\""); },
       "spheres[0].radius: expected a number, got string \"NaN\""},
      {"Infinity as a string", [] { return edit("[0, 0.5, 0]", "[0, \"Infinity\", 0]"); },
       "spheres[0].center[1]: expected a number, got string \"Infinity\""},
      {"1e999", [] { return edit("\"radius\": 0.5", "\"radius\": 1e999"); },
       "invalid JSON: number overflow parsing '1e999'"},
      {"-1e999", [] { return edit("[0, 0.5, 0]", "[0, 0.5, -1e999]"); },
       "invalid JSON: number overflow parsing '-1e999'"},
      {"1e39", [] { return edit("\"radius\": 0.5", "\"radius\": 1e39"); },
       "spheres[0].radius: out of range of a 32-bit float (got 1e+39)"},
      // Sizes.
      {"zero radius", [] { return edit("\"radius\": 0.5", "\"radius\": 0"); },
       "spheres[0].radius: must be greater than 0 (got 0)"},
      {"negative radius", [] { return edit("\"radius\": 0.5", "\"radius\": -2"); },
       "spheres[0].radius: must be greater than 0 (got -2)"},
      {"negative film width", [] { return edit("\"width\": 64", "\"width\": -64"); },
       "film.width: must be an integer in [1, 16384] (got -64)"},
      {"0x0 film", [] { return edit("\"width\": 64, \"height\": 32", "\"width\": 0, \"height\": 0"); },
       "film.width: must be an integer in [1, 16384] (got 0)"},
      {"100000x100000 film",
       [] { return edit("\"width\": 64, \"height\": 32", "\"width\": 100000, \"height\": 100000"); },
       "film.width: must be an integer in [1, 16384] (got 100000); a 100000x100000 film would "
       "need 633.3 GiB of GPU buffers (68 bytes per pixel), the limit is 4.2 GiB (67108864 "
       "pixels, e.g. 8192x8192)"},
      {"16384x16384 film",
       [] { return edit("\"width\": 64, \"height\": 32", "\"width\": 16384, \"height\": 16384"); },
       "film: a 16384x16384 film would need 17.0 GiB of GPU buffers (68 bytes per pixel), the "
       "limit is 4.2 GiB (67108864 pixels, e.g. 8192x8192)"},
      {"2^64 film height", [] { return edit("\"height\": 32", "\"height\": 18446744073709551615"); },
       "film.height: must be an integer in [1, 16384] (got 9223372036854775807); a "
       "64x9223372036854775807 film would need 37383395344384.0 GiB of GPU buffers (68 bytes "
       "per pixel), the limit is 4.2 GiB (67108864 pixels, e.g. 8192x8192)"},
      {"2^20 + 1 spheres", [&] { return edit("\"spheres\": [{", "\"spheres\": " + huge_list + ", \"quads\": [{"); },
       "spheres: too many spheres: 1048577 (the limit is 1048576, so that their GPU array fits "
       "the 128 MiB that OpenGL 4.5 guarantees for a shader storage block)"},
      // Limits of the renderer's 32-bit floats, on the values the GPU sees.
      {"environment colour 3e38 times intensity 3e38",
       [] { return edit("\"environment\": {\"texture\": \"sky.hdr\"}", "\"environment\": {\"color\": [3e38, 0, 0], \"intensity\": 3e38}"); },
       "environment.intensity: times environment.color[0] (3e+38) gives a radiance of inf, above "
       "the limit of 1e+20 (the renderer sums radiance in 32-bit floats)"},
      {"textured environment of intensity 3e38", [] { return edit("\"texture\": \"sky.hdr\"", "\"texture\": \"sky.hdr\", \"intensity\": 3e38"); },
       "environment.intensity: must be at most 1e+20 (got 3e+38) (the renderer sums radiance in "
       "32-bit floats)"},
      {"emission 3e38", [] { return edit("\"color_texture\": \"wood\"", "\"color_texture\": \"wood\", \"emission\": [0, 3e38, 0]"); },
       "materials[0].emission[1]: must be at most 1e+20 (got 3e+38) (the renderer sums radiance "
       "in 32-bit floats)"},
      {"sphere floor of radius 1e8 seen from 1 above",
       [] { return edit("\"center\": [0, 0.5, 0], \"radius\": 0.5", "\"center\": [0, -1e8, 0], \"radius\": 1e8"); },
       "spheres[0]: the camera is 1 from the surface (radius 1e+08), not farther than the 32-bit "
       "float rounding of the sphere's position (4): move the camera away or make the sphere "
       "smaller"},
      {"sphere of radius 2e12", [] { return edit("\"radius\": 0.5", "\"radius\": 2e12"); },
       "spheres[0].radius: must be at most 1e+12 in magnitude (got 2e+12) (beyond it the "
       "renderer's 32-bit float intersection overflows)"},
      {"quad floor of half-size 1e19",
       [] { return edit("\"material\": \"m\"}]", "\"material\": \"m\"}], \"quads\": [{\"material\": \"m\", \"corners\": "
                        "[[-1e19, 0, -1e19], [-1e19, 0, 1e19], [1e19, 0, -1e19], [1e19, 0, 1e19]]}]"); },
       "quads[0].corners[0][0]: must be at most 1e+12 in magnitude (got -1e+19) (beyond it the "
       "renderer's 32-bit float intersection overflows)"},
      // Images: missing, cut, corrupted, not an image.
      {"missing texture", [] { return edit("wood.png", "missing.png"); },
       "textures[0].path: cannot read image: {dir}/missing.png: file not found"},
      {"truncated PNG texture", [] { return edit("wood.png", "cut-wood.png"); },
       "textures[0].path: cannot read image: {dir}/cut-wood.png: file is truncated (chunk 'IDAT' "
       "at byte 33 runs past the end)"},
      {"corrupt PNG texture", [] { return edit("wood.png", "flip-wood.png"); },
       "textures[0].path: cannot read image: {dir}/flip-wood.png: corrupt PNG (CRC mismatch in "
       "chunk 'IDAT' at byte 33)"},
      {"project file as texture", [] { return edit("wood.png", "p.glint"); },
       "textures[0].path: cannot read image: {dir}/p.glint: not an image in a supported format "
       "(PNG, JPEG, Radiance HDR, OpenEXR)"},
      {"folder as texture", [] { return edit("wood.png", "."); },
       "textures[0].path: cannot read image: {dir}/.: is a directory, not an image"},
      {"device as texture", [] { return edit("wood.png", "/dev/zero"); },
       "textures[0].path: cannot read image: /dev/zero: not a regular file"},
      {"missing environment", [] { return edit("sky.hdr", "nope.exr"); },
       "environment.texture: cannot read image: {dir}/nope.exr: file not found"},
      // Not UTF-8, nested too deep, or followed by more than whitespace.
      {"UTF-16 little-endian with a byte order mark", [] { return "\xff\xfe" + utf16(kValid, false); },
       "not UTF-8 (looks like UTF-16 little-endian, with a byte order mark); a project file is "
       "JSON text in UTF-8"},
      {"UTF-16 big-endian with a byte order mark", [] { return "\xfe\xff" + utf16(kValid, true); },
       "not UTF-8 (looks like UTF-16 big-endian, with a byte order mark); a project file is JSON "
       "text in UTF-8"},
      {"UTF-16 little-endian without a byte order mark", [] { return utf16(kValid, false); },
       "not UTF-8 (looks like UTF-16 little-endian); a project file is JSON text in UTF-8"},
      {"UTF-16 big-endian without a byte order mark", [] { return utf16(kValid, true); },
       "not UTF-8 (looks like UTF-16 big-endian); a project file is JSON text in UTF-8"},
      {"UTF-32 little-endian", [] { return utf16(utf16(kValid, false), false); },
       "not UTF-8 (looks like UTF-32 little-endian); a project file is JSON text in UTF-8"},
      {"NUL and garbage after the document", [] { return kValid + std::string("\0garbage", 8); },
       "trailing content after the JSON document at line 6, column " + std::to_string(kValid.size() - kValid.rfind('\n')) +
           " (a NUL byte; only whitespace may follow the document)"},
      {"NUL in a string", [] { return edit("\"ball\"", std::string("\"b\0\"", 4)); },
       "invalid JSON: a NUL byte in a string at line 6, column 26 (write it as \\u0000)"},
      {"NUL inside the document", [] { return edit("\"ball\",", std::string("\"ball\",\0", 8)); },
       "invalid JSON: a NUL byte at line 6, column 31"},
      {"text after the document", [] { return kValid + " x"; },
       "invalid JSON: parse error at line 6, column 89: syntax error while parsing value - "
       "invalid literal; last read: '\"m\"}]} x'; expected end of input"},
      {"100 KB of [", [] { return std::string(100000, '['); },
       "invalid JSON: arrays and objects nested deeper than 256 levels at line 1, column 257"},
      // The radius is in the third level (the root, spheres, spheres[0]).
      {"257 levels in a value", [] { return edit("\"radius\": 0.5", "\"radius\": " + std::string(254, '[')); },
       "invalid JSON: arrays and objects nested deeper than 256 levels at line 6, column 318"},
      {"256 levels in a value", [] { return edit("\"radius\": 0.5", "\"radius\": " + std::string(253, '[') + std::string(253, ']')); },
       "spheres[0].radius: expected a number, got an array of 1"},
      // User strings in messages are clipped (a 1 MB key or name is not repeated in full).
      {"1 MB unknown key", [] { return edit("\"radius\"", "\"" + std::string(1 << 20, 'k') + "\""); },
       "spheres[0]." + std::string(31, 'k') + "..." + std::string(30, 'k') +
           ": unknown key (expected one of: name, center, radius, material)"},
      {"1 MB duplicate key", [] { const std::string k = "\"" + std::string(1 << 20, 'k') + "\": 1"; return edit("\"radius\": 0.5", k + ", " + k); },
       "spheres[0]." + std::string(31, 'k') + "..." + std::string(30, 'k') + ": duplicate key"},
      {"1 MB string for a number", [] { return edit("\"radius\": 0.5", "\"radius\": \"" + std::string(1 << 20, '7') + "\""); },
       "spheres[0].radius: expected a number, got string \"" + std::string(31, '7') + "..." +
           std::string(30, '7') + "\""},
      {"1 MB material name", [] { return edit("\"material\": \"m\"", "\"material\": \"" + std::string(1 << 20, 'm') + "\""); },
       "spheres[0].material: unknown material \"" + std::string(31, 'm') + "..." +
           std::string(30, 'm') + "\""},
      {"1 MB of a bad literal", [] { return edit("\"radius\": 0.5", "\"radius\": t" + std::string(1 << 20, 'x')); },
       "invalid JSON: parse error at line 6, column 66: syntax error while parsing value - "
       "invalid literal; last read: '\"radius\": tx'"},
      {"NUL in a texture path", [] { return edit("\"wood.png\"", "\"wood.png\\u0000.txt\""); },
       "textures[0].path: contains a NUL character (\\u0000), which no file name can hold"},
      {"NUL in the environment path", [] { return edit("\"sky.hdr\"", "\"sky.hdr\\u0000\""); },
       "environment.texture: contains a NUL character (\\u0000), which no file name can hold"},
      // Images that pass the header probe: decoded on load, so that the error names the project
      // and the JSON path (not only at render time, without either).
      {"PNG texture with a short IDAT", [] { return edit("wood.png", "short-idat.png"); },
       "textures[0].path: cannot read image: {dir}/short-idat.png: cannot decode image (bad huffman code)"},
      {"EXR texture without RGB", [] { return edit("wood.png", "no-rgb.exr"); },
       "textures[0].path: cannot read image: {dir}/no-rgb.exr: OpenEXR file has neither R, G, B "
       "nor a single grey channel"},
      {"EXR environment with an offset past the end", [] { return edit("sky.hdr", "far-offset.exr"); },
       "environment.texture: cannot read image: {dir}/far-offset.exr: cannot decode OpenEXR data "
       "(Invalid offset value in DecodeEXRImage.)"},
      {"NaN in the environment", [] { return edit("sky.hdr", "nan.exr"); },
       "environment.texture: cannot read image: {dir}/nan.exr: texel (3, 2) channel G is nan "
       "(texels must be finite and not negative)"},
      {"negative environment", [] { return edit("sky.hdr", "negative.exr"); },
       "environment.texture: cannot read image: {dir}/negative.exr: texel (0, 0) channel R is -5 "
       "(texels must be finite and not negative)"},
      {"infinite texture alpha", [] { return edit("wood.png", "inf.exr"); },
       "textures[0].path: cannot read image: {dir}/inf.exr: texel (1, 3) channel A is inf "
       "(texels must be finite and not negative)"},
      {"environment texel times intensity past the radiance limit",
       [] { return edit("\"sky.hdr\"", "\"bright.exr\", \"intensity\": 1e10"); },
       "environment.intensity: times the brightest texel of the environment (1e+30) gives a "
       "radiance of 1e+40, above the limit of 1e+20 (the renderer's 32-bit floats would overflow)"},
      // Memory: estimated from the headers, refused before anything is decoded.
      {"16384x16384 PNG texture", [] { return edit("wood.png", "bomb.png"); },
       "textures[0].path: {dir}/bomb.png: a 16384x16384 8-bit texture takes 1.0 GiB (4 bytes per "
       "texel), which brings the textures and environment to 1.0 GiB; the limit is 768.0 MiB"},
      {"16384x8192 HDR environment", [] { return edit("sky.hdr", "bomb.hdr"); },
       "environment.texture: {dir}/bomb.hdr: a 16384x8192 float environment takes 2.5 GiB (20 "
       "bytes per texel), which brings the textures and environment to 2.5 GiB; the limit is "
       "768.0 MiB"},
      {"texture path with invalid UTF-8 escape", [] { return edit("wood.png", "w\\ud800.png"); },
       "invalid JSON: parse error at line 4, column 49: syntax error while parsing value - "
       "invalid string: surrogate U+D800..U+DBFF must be followed by U+DC00..U+DFFF; last read: "
       "'\"w\\ud800.'"},
  };
  const fs::path file = dir / "p.glint";
  write_bytes(file, kValid);
  ASSERT_NO_THROW(load_project(file));  // each row fails for its own reason only
  for (const ProjectRow& row : rows) {
    SCOPED_TRACE(row.what);
    write_bytes(file, row.text());
    try {
      load_project(file);
      ADD_FAILURE() << "loaded";
    } catch (const ProjectError& e) {
      EXPECT_EQ(e.file, file.string());
      EXPECT_EQ(std::string(e.what()), file.string() + ": " + replace_dir(row.message, dir));
      EXPECT_LE(std::string(e.what()).size(), 600u);
    }
  }
  // A UTF-8 byte order mark is accepted (nlohmann skips it).
  write_bytes(file, "\xef\xbb\xbf" + kValid);
  EXPECT_EQ(load_project(file).spheres.at(0).name, "ball");
}

struct ImageRow {
  const char* what;
  const char* source;                               // a valid file written by save_image
  std::function<std::string(std::string)> damage;   // its bytes -> the broken file's bytes
  std::string message;                              // exactly what() after "FILE: "
};

// Overwrites the first occurrence of `from` (a header field) with `to`, of the same length.
std::function<std::string(std::string)> patch(std::string from, std::string to) {
  return [=](std::string bytes) {
    const size_t at = bytes.find(from);
    if (at == std::string::npos || from.size() != to.size()) throw std::logic_error("patch: " + from);
    return bytes.replace(at, from.size(), to);
  };
}
std::function<std::string(std::string)> cut_to(size_t length) {
  return [=](std::string bytes) { return bytes.substr(0, length); };
}
std::function<std::string(std::string)> flip(size_t at) {
  return [=](std::string bytes) {
    bytes.at(at) ^= 0x5a;
    return bytes;
  };
}

// Sets max_x of the EXR data window (attribute "dataWindow", type "box2i", 4 bytes of size,
// then min_x, min_y, max_x, max_y as little-endian int32).
std::function<std::string(std::string)> data_window_max_x(std::string le32) {
  return [=](std::string bytes) {
    const size_t at = bytes.find(std::string("dataWindow\0box2i\0", 17));
    if (at == std::string::npos) throw std::logic_error("no dataWindow");
    return bytes.replace(at + 17 + 4 + 8, 4, le32);
  };
}

TEST(MalformedInput, ImagesFailWithFileAndProblem) {
  TempDir tmp;
  const fs::path& dir = tmp.path();
  save_image(dir / "a.png", pattern(24, 16));
  save_image(dir / "a.hdr", pattern(24, 16));   // run-length encoded scanlines (width >= 8)
  save_image(dir / "a.exr", pattern(24, 16));   // float32 RGBA, uncompressed scanlines
  // save_image writes ZIP-compressed EXR (one block of 16 lines): the offset table (one
  // 8-byte entry) follows the null byte that ends the header, whose last attribute tinyexr
  // writes is screenWindowWidth (a float).
  const size_t exr_table = read_bytes(dir / "a.exr").find(std::string("screenWindowWidth\0float\0", 24)) + 24 + 4 + 4 + 1;
  const std::vector<ImageRow> rows = {
      {"PNG cut in the signature", "a.png", cut_to(5),
       "not an image in a supported format (PNG, JPEG, Radiance HDR, OpenEXR)"},
      {"PNG cut in IHDR", "a.png", cut_to(20),
       "file is truncated (chunk 'IHDR' at byte 8 runs past the end)"},
      {"PNG cut in IDAT", "a.png", cut_to(100),
       "file is truncated (chunk 'IDAT' at byte 33 runs past the end)"},
      {"PNG without IEND", "a.png", [](std::string b) { return b.substr(0, b.size() - 12); },
       "file is truncated (no IEND chunk)"},
      {"PNG with a corrupt IHDR", "a.png", flip(17),
       "corrupt PNG (CRC mismatch in chunk 'IHDR' at byte 8)"},
      {"PNG with a corrupt IDAT", "a.png", flip(60),
       "corrupt PNG (CRC mismatch in chunk 'IDAT' at byte 33)"},
      {"PNG chunk length past the end", "a.png", patch(std::string("\0\0\0\x0dIHDR", 8), std::string("\x7f\0\0\x0dIHDR", 8)),
       "file is truncated (chunk 'IHDR' at byte 8 runs past the end)"},
      {"HDR cut in the header", "a.hdr", cut_to(30), "file is truncated (incomplete image header)"},
      {"HDR cut in the pixels", "a.hdr", [](std::string b) { return b.substr(0, b.size() / 2); },
       "file is truncated"},
      {"HDR with a corrupt format line", "a.hdr", patch("32-bit_rle_rgbe", "32-bit_rle_xyze"),
       "not a readable image (unknown image type)"},
      {"HDR with a corrupt size line", "a.hdr", patch("-Y 16 +X 24", "-Y 16 -X 24"),
       "not a readable image (unknown image type)"},
      {"HDR with a zero size", "a.hdr", patch("-Y 16 +X 24", "-Y 00 +X 24"),
       "invalid image size 24x0"},
      {"EXR cut in the header", "a.exr", cut_to(40),
       "bad OpenEXR header (Failed to read attribute.)"},
      {"EXR cut in the pixels", "a.exr", [](std::string b) { return b.substr(0, b.size() - 20); },
       "cannot decode OpenEXR data (Invalid data found when decoding pixels.)"},
      {"EXR with a corrupt magic", "a.exr", flip(0),
       "not an image in a supported format (PNG, JPEG, Radiance HDR, OpenEXR)"},
      {"EXR with a corrupt channel list", "a.exr", patch("channels", "chbnnels"),
       "bad OpenEXR header (\"channels\" attribute not found in the header.)"},
      {"EXR with a huge data window", "a.exr", data_window_max_x("\xff\xff\xff\x7f"),
       "image is too large (16385x16, the limit is 16384 per side)"},
      {"EXR with an inverted data window", "a.exr", data_window_max_x("\xfe\xff\xff\xff"),
       "invalid image size -1x16"},
      {"EXR marked tiled with a 2-byte tiles attribute", "a.exr",
       [](std::string b) {
         b.at(5) |= 0x02;  // the version field's "single-part tiled" bit (bit 9)
         return b.insert(8, std::string("tiles\0tiledesc\0\x02\0\0\0\x10\x00", 21));
       },
       "bad OpenEXR header (attribute 'tiles' is 2 bytes, not 9)"},
      {"EXR with a corrupt offset table", "a.exr",
       [&](std::string b) { b.at(exr_table + 3) = '\x7f'; return b; },
       "cannot decode OpenEXR data (Invalid offset value in DecodeEXRImage.)"},
      {"EXR with corrupt ZIP data", "a.exr", [](std::string b) { b.at(b.size() - 6) ^= 0x5a; return b; },
       "cannot decode OpenEXR data (Invalid data found when decoding pixels.)"},
      {"empty file", "a.png", cut_to(0), "file is empty"},
  };
  for (const ImageRow& row : rows) {
    SCOPED_TRACE(row.what);
    const fs::path file = dir / (std::string("broken") + fs::path(row.source).extension().string());
    write_bytes(file, row.damage(read_bytes(dir / row.source)));
    try {
      load_image(file, ColorEncoding::srgb);
      ADD_FAILURE() << "loaded";
    } catch (const ImageError& e) {
      EXPECT_EQ(std::string(e.what()), file.string() + ": " + row.message);
    }
  }
  // Missing files and folders, for both the header probe and the full load.
  for (const auto& [file, message] :
       {std::pair{dir / "missing.exr", std::string("file not found")},
        std::pair{dir, std::string("is a directory, not an image")}}) {
    for (bool probe : {true, false}) {
      try {
        probe ? (void)probe_image(file) : (void)load_image(file, ColorEncoding::linear);
        ADD_FAILURE() << file << " loaded";
      } catch (const ImageError& e) {
        EXPECT_EQ(std::string(e.what()), file.string() + ": " + message);
      }
    }
  }
}

// File names are bytes on Linux: a folder named in Latin-1 ("caf\xe9") is not UTF-8. Loading
// from it works and errors name it as it is; saving a texture path that runs through it into a
// JSON file (which must be UTF-8) is an error naming the JSON path, and leaves no file behind.
TEST(MalformedInput, PathsThatAreNotUtf8) {
  TempDir tmp;
  const fs::path latin1 = tmp.path() / "caf\xe9";
  fs::create_directories(latin1);
  save_image(latin1 / "wood.png", pattern(8, 8));
  save_image(latin1 / "sky.hdr", pattern(16, 8));
  write_bytes(latin1 / "p.glint", kValid);
  const Scene scene = load_project(latin1 / "p.glint");
  EXPECT_EQ(scene.textures.at(0).path, "wood.png");

  write_bytes(latin1 / "bad.glint", edit("wood.png", "missing.png"));
  try {
    load_project(latin1 / "bad.glint");
    ADD_FAILURE() << "loaded";
  } catch (const ProjectError& e) {
    EXPECT_EQ(std::string(e.what()), (latin1 / "bad.glint").string() +
                                         ": textures[0].path: cannot read image: " +
                                         (latin1 / "missing.png").string() + ": file not found");
  }

  // Saved elsewhere, the texture path becomes "../caf\xe9/wood.png": not storable in JSON.
  const fs::path other = tmp.path() / "other" / "p.glint";
  fs::create_directories(other.parent_path());
  try {
    save_project(scene, other);
    ADD_FAILURE() << "saved";
  } catch (const ProjectError& e) {
    EXPECT_EQ(std::string(e.what()),
              other.string() + ": environment.texture: is not valid UTF-8, which a JSON file "
                               "cannot hold (rename the file or folder)");
  }
  EXPECT_FALSE(fs::exists(other));
  EXPECT_TRUE(fs::is_empty(other.parent_path()));

  // Names set through the API are validated without throwing on their bytes.
  Scene named = scene;
  named.spheres.at(0).material = "m\xff";
  const auto problems = validate_scene(named, false);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_STREQ(problems[0].what(), "spheres[0].material: unknown material \"m\xef\xbf\xbd\"");
}

// A project that is a device, a FIFO or a link to one is refused without reading it (a link to
// /dev/zero grew until std::bad_alloc, a FIFO blocked), and so is one over kMaxProjectBytes
// (a sparse file: no disk space used).
TEST(MalformedInput, ProjectsThatAreNotRegularFilesOrTooLarge) {
  TempDir tmp;
  const fs::path zero = tmp.path() / "zero.glint", fifo = tmp.path() / "fifo.glint",
                 large = tmp.path() / "large.glint";
  fs::create_symlink("/dev/zero", zero);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  {
    std::ofstream(large) << kValid;
  }
  fs::resize_file(large, kMaxProjectBytes + 1);
  const fs::path loop = tmp.path() / "loop.glint";
  fs::create_symlink(loop, loop);
  const std::pair<fs::path, std::string> cases[] = {
      {zero, "not a regular file (a device, FIFO or socket)"},
      {"/dev/zero", "not a regular file (a device, FIFO or socket)"},
      {fifo, "not a regular file (a device, FIFO or socket)"},
      {large, "file is too large (1073741825 bytes, the limit is 1073741824 = 1.0 GiB)"},
      {loop, "cannot open: Too many levels of symbolic links"},
  };
  for (const auto& [file, message] : cases) {
    try {
      load_project(file);
      ADD_FAILURE() << file << " loaded";
    } catch (const ProjectError& e) {
      EXPECT_EQ(std::string(e.what()), file.string() + ": " + message);
    }
  }
}

// Every part of a message is clipped in its middle: a long file name keeps its start and its
// end, and no message exceeds a few hundred characters, whatever the strings it quotes.
TEST(MalformedInput, MessagesStayShort) {
  const std::string file = "/" + std::string(4000, 'd') + "/p.glint";
  const ProjectError e(file, "spheres[0]." + std::string(1 << 20, 'k'), std::string(1 << 20, 'p') + " (why)");
  const std::string what = e.what();
  EXPECT_LE(what.size(), 600u);
  EXPECT_EQ(what.substr(0, 10), "/ddddddddd");
  EXPECT_NE(what.find("d/p.glint: spheres[0].kkk"), std::string::npos) << what;
  EXPECT_EQ(what.substr(what.size() - 8), "pp (why)") << what;
  EXPECT_EQ(e.file, file);
  EXPECT_LE(e.json_path.size(), 120u);
  EXPECT_LE(e.problem.size(), 300u);
  // Clipping never splits a UTF-8 sequence: 2-byte characters stay whole on both sides.
  std::string twobyte;
  for (int i = 0; i < 400; ++i) twobyte += "\xc3\xa9";
  const std::string clipped = ProjectError("", "", twobyte).what();
  EXPECT_EQ(clipped.size() % 2, 1u);  // whole 2-byte characters and the 3 dots
  EXPECT_NE(clipped.find("\xc3\xa9...\xc3\xa9"), std::string::npos);
}

// 10^6 spheres are within the stated limit (kMaxSpheres = 2^20): they load, whole.
TEST(MalformedInput, AMillionSpheresLoad) {
  TempDir tmp;
  std::string text = R"({"format": "glint-project", "version": 1, "materials": [{"name": "m"}],
    "spheres": [)";
  constexpr int kCount = 1000000;
  text.reserve(text.size() + kCount * 64);
  for (int i = 0; i < kCount; ++i) {
    text += i ? "," : "";
    text += "{\"center\":[" + std::to_string(i % 1000) + "," + std::to_string(i / 1000) +
            ",0],\"radius\":0.25,\"material\":\"m\"}";
  }
  text += "]}";
  const fs::path file = tmp.path() / "million.glint";
  write_bytes(file, text);
  const auto start = std::chrono::steady_clock::now();
  const Scene scene = load_project(file);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(scene.spheres.size(), size_t(kCount));
  EXPECT_EQ(scene.spheres.back().center, glm::vec3(999, 999, 0));
  RecordProperty("load_seconds", std::to_string(seconds));
  std::printf("10^6 spheres (%.0f MB of JSON) loaded in %.2f s\n", text.size() / 1e6, seconds);
}

// Degenerate quads are rejected on load, at every scale, with an error naming the file and the
// JSON path; quads that are tiny, huge or far from the origin but have an area load fine
// (the area test is relative to the quad's own size). A hard case (`ctest -R hard_`).
TEST(hard_Load, DegenerateQuadsAreRejectedNamingThePath) {
  TempDir tmp;
  auto write = [&](const std::string& corners) {
    const fs::path file = tmp / "degenerate.glint";
    std::ofstream(file) << R"({"format": "glint-project", "version": 1,
      "materials": [{"name": "m"}],
      "quads": [{"name": "ok", "material": "m", "corners": [[0,0,0],[0,1,0],[1,0,0],[1,1,0]]},
                {"name": "bad", "material": "m", "corners": )" << corners << "}]}";
    return file;
  };
  const std::vector<std::string> degenerate = {
      "[[0,0,0],[1,1,1],[2,2,2],[3,3,3]]",              // collinear
      "[[5,5,5],[5,5,5],[5,5,5],[5,5,5]]",              // one point
      "[[0,0,0],[1,0,0],[0,1,0],[1,0,0]]",              // p3 = p1: second triangle empty
      "[[0,0,0],[0,0,0],[1,0,0],[1,1,0]]",              // p1 = p0: first triangle empty
      "[[1e-6,0,0],[0,1e-6,0],[2e-6,-1e-6,0],[1e-6,1e-6,0]]",  // collinear and tiny
      "[[1e5,0,0],[1e5,1e3,0],[1e5,2e3,0],[1e5,3e3,0]]",       // collinear and far
      // Distinct in the file, equal once rounded to float (ulp(1e6) = 0.0625): a line.
      "[[1000000,0,0],[1000000.01,0,0],[1000000,0,5],[1000000.01,0,5]]",
  };
  for (const std::string& corners : degenerate) {
    const fs::path file = write(corners);
    try {
      load_project(file);
      ADD_FAILURE() << "accepted " << corners;
    } catch (const ProjectError& e) {
      EXPECT_EQ(e.file, file.string()) << corners;
      EXPECT_EQ(e.json_path, "quads[1].corners") << corners;
      EXPECT_NE(e.problem.find("zero-area quad"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(file.string() + ": quads[1].corners: zero-area"), std::string::npos)
          << e.what();
    }
  }
  const std::vector<std::string> valid = {
      "[[0,0,0],[0,1e-6,0],[1e-6,0,0],[1e-6,1e-6,0]]",            // tiny
      "[[-1e5,0,-1e5],[-1e5,0,1e5],[1e5,0,-1e5],[1e5,0,1e5]]",    // huge
      "[[1e5,1e5,1e5],[1e5,100001,1e5],[100001,1e5,1e5],[100001,100001,1e5]]",  // far
      "[[0,0,0],[3,0.1,0],[1,2,0],[4,2.1,0]]",                     // sheared parallelogram
  };
  for (const std::string& corners : valid) {
    EXPECT_NO_THROW(load_project(write(corners))) << corners;
  }
}


}  // namespace
}  // namespace glint
