// Text metadata in written images (renderer/image_metadata.h): what save_image and
// save_exr_layers write is what read_image_metadata reads back, in order, for PNG (tEXt, and
// iTXt beyond ASCII), Radiance (header lines) and OpenEXR (string attributes); the image itself
// still loads; entries that a format cannot hold are refused; damaged files are errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/image.h"
#include "renderer/image_metadata.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {
namespace fs = std::filesystem;

Image gradient(int w, int h) {
  Image img;
  img.width = w;
  img.height = h;
  img.pixels.resize(static_cast<size_t>(w) * h * 4);
  for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = (i % 4 == 3) ? 1.0f : float(i % 97) / 96.0f;
  return img;
}

const ImageMetadata kEntries = {{"Software", "Glint 0.1 (42cfb04d0e1a-dirty)"},
                                {"glint.digest", "0123456789abcdef"},
                                {"glint.spp", "64"},
                                {"Comment", "caf\xc3\xa9 = \xe2\x9c\x93"}};  // UTF-8: an iTXt chunk in a PNG

std::vector<unsigned char> read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& file, const std::vector<unsigned char>& bytes) {
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

// `entries` appear in `all`, in this order (a Radiance header also holds its FORMAT line).
bool contains_in_order(const ImageMetadata& all, const ImageMetadata& entries) {
  auto at = all.begin();
  for (const auto& entry : entries) {
    at = std::find(at, all.end(), entry);
    if (at == all.end()) return false;
  }
  return true;
}

TEST(ImageMetadata, RoundTripsInEveryFormatAndTheImageStillLoads) {
  test::TempDir dir;
  const Image image = gradient(7, 5);
  for (const char* ext : {".png", ".hdr", ".exr"}) {
    const fs::path plain = dir / (std::string("plain") + ext), tagged = dir / (std::string("tagged") + ext);
    save_image(plain, image);
    save_image(tagged, image, kEntries);
    const ImageMetadata read = read_image_metadata(tagged);
    if (std::string(ext) == ".hdr") {
      EXPECT_TRUE(contains_in_order(read, kEntries)) << ext;
    } else {
      EXPECT_EQ(read, kEntries) << ext;
    }
    for (const auto& [key, value] : read_image_metadata(plain))  // a Radiance file's FORMAT line
      EXPECT_TRUE(key == "FORMAT" || key == "EXPOSURE") << ext << ": " << key;
    EXPECT_EQ(load_image(tagged, ColorEncoding::linear).pixels, load_image(plain, ColorEncoding::linear).pixels)
        << ext;
  }
}

TEST(ImageMetadata, ExrLayersCarryTheMetadata) {
  test::TempDir dir;
  const Image image = gradient(4, 3);
  save_exr_layers(dir / "layers.exr", {{"", &image, "RGBA"}, {"albedo", &image, "RGB"}}, kEntries);
  EXPECT_EQ(read_image_metadata(dir / "layers.exr"), kEntries);
  EXPECT_EQ(load_exr_layer(dir / "layers.exr", "albedo").width, 4);
}

TEST(ImageMetadata, EntriesAFormatCannotHoldAreRefusedNamingTheFile) {
  test::TempDir dir;
  const Image image = gradient(2, 2);
  for (const ImageMetadata& bad : {ImageMetadata{{"a=b", "x"}}, ImageMetadata{{"", "x"}},
                                   ImageMetadata{{std::string(80, 'k'), "x"}}, ImageMetadata{{" key", "x"}},
                                   ImageMetadata{{"key", "two\nlines"}}, ImageMetadata{{"k\xc3\xa9", "x"}}}) {
    for (const char* ext : {".png", ".hdr", ".exr"}) {
      const fs::path file = dir / (std::string("bad") + ext);
      try {
        save_image(file, image, bad);
        ADD_FAILURE() << ext << ": '" << bad[0].first << "' was written";
      } catch (const ImageError& e) {
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
      }
      EXPECT_FALSE(fs::exists(file)) << ext;
    }
  }
}

TEST(ImageMetadata, DamagedFilesAreErrors) {
  test::TempDir dir;
  save_image(dir / "ok.png", gradient(3, 3), kEntries);
  std::vector<unsigned char> png = read_bytes(dir / "ok.png");
  // A flipped byte inside the first text chunk's data (after the signature and IHDR: 33 bytes,
  // then the chunk's length and type).
  png[33 + 8 + 2] ^= 0x20;
  write_bytes(dir / "crc.png", png);
  EXPECT_THROW(read_image_metadata(dir / "crc.png"), ImageError);
  // A text chunk whose length runs past the end of the file.
  png = read_bytes(dir / "ok.png");
  png.resize(33 + 20);
  write_bytes(dir / "short.png", png);
  EXPECT_THROW(read_image_metadata(dir / "short.png"), ImageError);
  // A Radiance header that never ends.
  const std::string endless = "#?RADIANCE\nSoftware=x\n";
  write_bytes(dir / "endless.hdr", {endless.begin(), endless.end()});
  EXPECT_THROW(read_image_metadata(dir / "endless.hdr"), ImageError);
  EXPECT_THROW(read_image_metadata(dir / "missing.png"), ImageError);
  fs::create_directory(dir / "folder.png");
  EXPECT_THROW(read_image_metadata(dir / "folder.png"), ImageError);
}

TEST(ImageMetadata, TextGoesIntoAPngOfAnotherEncoder) {
  // A PNG that stb_image_write did not write (the project's checker texture): the chunks go
  // after its IHDR, the decoder's CRC checks (image_io.cpp) pass and the pixels are unchanged.
  const std::vector<unsigned char> original = read_bytes(fs::path(GLINT_SOURCE_DIR) / "projects/assets/checker.png");
  const std::vector<unsigned char> tagged = with_png_text(original, kEntries);
  EXPECT_TRUE(contains_in_order(read_png_text(tagged, "checker.png"), kEntries));
  EXPECT_EQ(load_image_data(tagged, "tagged", ColorEncoding::linear).pixels,
            load_image_data(original, "original", ColorEncoding::linear).pixels);
  EXPECT_THROW(with_png_text({'G', 'I', 'F', '8'}, kEntries), std::invalid_argument);
}

}  // namespace
}  // namespace glint
