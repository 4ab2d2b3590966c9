// The rules for what users type, shared by the commands and the editor: integers
// (renderer/parse_number.h) and an output image's format (output_format_problem, image.h).
#include <gtest/gtest.h>

#include "renderer/image.h"
#include "renderer/parse_number.h"

namespace glint {
namespace {

TEST(UserInput, IntegersAreTheWholeTextWithinTheirRange) {
  EXPECT_EQ(parse_integer("12", 1, 20), 12);
  EXPECT_EQ(parse_integer("20", 1, 20), 20);
  EXPECT_EQ(parse_integer("+3", 1, 20), 3);
  EXPECT_EQ(parse_integer("0", 0, 4294967295L), 0);
  EXPECT_EQ(parse_integer("4294967295", 0, 4294967295L), 4294967295L);
  for (const char* bad : {"", "0", "21", "-1", "12x", "1.5", "x", "99999999999999999999999"})
    EXPECT_EQ(parse_integer(bad, 1, 20), std::nullopt) << bad;
  EXPECT_EQ(integer_expected("--spp", 1, 1073741824, "0"), "--spp expects an integer from 1 to 1073741824, got '0'");
}

TEST(UserInput, OutputImagesArePngHdrOrExrAsTyped) {
  for (const char* good : {"a.png", "dir/b.hdr", "/abs/c.exr", ".d.exr"})
    EXPECT_EQ(output_format_problem(good), std::nullopt) << good;
  for (const char* bad : {"a.jpg", "a", "a.PNG", "a.exr.tmp", "dir.png/"})
    EXPECT_EQ(output_format_problem(bad), "must end in .png, .hdr or .exr") << bad;
}

}  // namespace
}  // namespace glint
