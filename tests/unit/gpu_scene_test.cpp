// Packing a scene for the GPU (renderer/gpu_scene.h): texture layers per file and encoding,
// material slots, quad normals.
#include <gtest/gtest.h>

#include "renderer/gpu_scene.h"

namespace glint {
namespace {

Scene sample_scene() {
  Scene s;
  s.textures.push_back({.name = "wood", .path = "wood.png"});
  s.materials.push_back({.name = "m", .color_texture = "wood"});
  s.spheres.push_back({.name = "a", .center = {0, 0, 0}, .radius = 1, .material = "m"});
  s.quads.push_back({.name = "q", .material = "m",
                     .corners = {glm::vec3{0, 0, 0}, glm::vec3{0, 1, 0}, glm::vec3{1, 0, 0}, glm::vec3{1, 1, 0}}});
  return s;
}

TEST(GpuScene, PacksOneLayerPerTextureAndEncoding) {
  Scene s = sample_scene();
  s.materials.push_back({.name = "rough", .roughness_texture = "wood"});
  s.materials.push_back({.name = "same", .color_texture = "wood"});
  PackedScene p = pack_scene(s);
  ASSERT_EQ(p.layers.size(), 2u);  // wood as sRGB colour, wood as linear roughness
  EXPECT_EQ(p.materials[0].layers.x, 0);
  EXPECT_EQ(p.materials[1].layers.z, 1);
  EXPECT_EQ(p.materials[2].layers.x, 0);
  EXPECT_EQ(p.materials[1].layers.x, -1);
  EXPECT_EQ(p.layers[1].encoding, ColorEncoding::linear);
  // The quad's normal follows docs/DESIGN.md: normalize(cross(p1 - p0, p2 - p0)).
  EXPECT_FLOAT_EQ(p.quads[0].normal.z, -1.0f);
}

}  // namespace
}  // namespace glint
