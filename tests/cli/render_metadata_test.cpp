// The provenance `glint render` writes into its images (renderer/render_metadata.h), read back
// from the files with the project's own readers: the Software that made it, the render's
// digest, its samples per pixel and its seed, in a PNG's text chunks, a Radiance header's lines
// and an OpenEXR header's string attributes. Runs the command in-process.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "app/render_command.h"
#include "renderer/build_info.h"
#include "renderer/image.h"
#include "renderer/image_metadata.h"
#include "renderer/render_metadata.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

const std::string kProject = std::string(GLINT_SOURCE_DIR) + "/projects/default.glint";

// `glint render ARGS...` (the arguments after "render"); its stderr is shown on failure.
void render(std::vector<std::string> args) {
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  testing::internal::CaptureStderr();
  const int code = run_render_command(static_cast<int>(argv.size()), argv.data());
  const std::string err = testing::internal::GetCapturedStderr();
  ASSERT_EQ(code, 0) << err;
}

std::map<std::string, std::string> metadata_of(const std::filesystem::path& file) {
  const ImageMetadata entries = read_image_metadata(file);
  return {entries.begin(), entries.end()};
}

TEST(RenderMetadata, EveryFormatCarriesTheProvenance) {
  test::TempDir dir;
  std::map<std::string, std::string> digests;
  for (const char* ext : {".png", ".hdr", ".exr"}) {
    const auto file = dir / (std::string("render") + ext);
    render({kProject, "-o", file.string(), "--width", "16", "--spp", "3", "--seed", "77"});
    const auto fields = metadata_of(file);
    EXPECT_EQ(fields.count(kMetadataSoftware) ? fields.at(kMetadataSoftware) : "", glint_software()) << ext;
    EXPECT_EQ(fields.count(kMetadataSpp) ? fields.at(kMetadataSpp) : "", "3") << ext;
    EXPECT_EQ(fields.count(kMetadataSeed) ? fields.at(kMetadataSeed) : "", "77") << ext;
    const std::string digest = fields.count(kMetadataDigest) ? fields.at(kMetadataDigest) : "";
    EXPECT_EQ(digest.size(), 16u) << ext << ": '" << digest << "'";
    EXPECT_EQ(digest.find_first_not_of("0123456789abcdef"), std::string::npos) << ext << ": '" << digest << "'";
    digests[ext] = digest;
    // The metadata leaves the image readable.
    EXPECT_EQ(probe_image(file).width, 16) << ext;
  }
  EXPECT_EQ(digests[".png"], digests[".exr"]);
  EXPECT_EQ(digests[".hdr"], digests[".exr"]);

  // The digest is a render part's: the final render's EXR names the render its parts belong to.
  const auto part = dir / "part.exr";
  render({kProject, "-o", part.string(), "--width", "16", "--samples", "0:3", "--seed", "77"});
  EXPECT_EQ(metadata_of(part).at("glint.digest"), digests[".exr"]);
  // Another seed is another render.
  const auto other = dir / "other.png";
  render({kProject, "-o", other.string(), "--width", "16", "--spp", "3", "--seed", "78"});
  EXPECT_NE(metadata_of(other).at(kMetadataDigest), digests[".png"]);
}

}  // namespace
}  // namespace glint
