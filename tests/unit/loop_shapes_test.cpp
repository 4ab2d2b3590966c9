// The uniform block of an unrolled closest-hit loop (renderer/loop_shapes.h,
// shaders/unrolled_loop.glsl).
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "renderer/loop_shapes.h"

namespace glint {
namespace {

// The block holds the first kLoopShapesMax shapes of each kind as the tables do, zeros after.
TEST(LoopShapes, BlockHoldsTheFirstShapesInTableOrder) {
  std::vector<GpuSphere> spheres(3);
  std::vector<GpuQuad> quads(kLoopShapesMax + 5);
  for (size_t i = 0; i < spheres.size(); ++i) spheres[i].center_radius = glm::vec4(float(i), 1, 2, 0.5f);
  for (size_t i = 0; i < quads.size(); ++i) quads[i].p0 = glm::vec4(float(i), 0, 0, 0);
  LoopShapesBlock block = loop_shapes_block(spheres, quads);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(block.spheres[i].center_radius.x, float(i));
  EXPECT_EQ(block.spheres[3].center_radius, glm::vec4(0));
  EXPECT_EQ(block.quads[kLoopShapesMax - 1].p0.x, float(kLoopShapesMax - 1));
  EXPECT_EQ(sizeof block, kLoopShapesMax * (32u + 128u));
}

// The shader declares the block with the sizes the C++ fills.
TEST(LoopShapes, ShaderBlockHasTheSizesOfTheCppBlock) {
  std::ifstream in(std::string(GLINT_SOURCE_DIR) + "/shaders/unrolled_loop.glsl");
  std::ostringstream text;
  text << in.rdbuf();
  const std::string source = text.str();
  std::smatch m;
  ASSERT_TRUE(std::regex_search(source, m, std::regex(R"(uniform LoopShapes \{\s*GpuSphere loop_spheres\[(\d+)\];\s*GpuQuad loop_quads\[(\d+)\];)")));
  EXPECT_EQ(std::stoi(m[1]), kLoopShapesMax);
  EXPECT_EQ(std::stoi(m[2]), kLoopShapesMax);
  EXPECT_NE(source.find("binding = " + std::to_string(kLoopShapesBinding) + ") uniform LoopShapes"),
            std::string::npos);
}

}  // namespace
}  // namespace glint
