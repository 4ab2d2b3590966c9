// Packing a scene for the GPU (renderer/gpu_scene.h): texture layers per file and encoding,
// material slots, quad normals.
#include <gtest/gtest.h>

#include "renderer/gpu_scene.h"

namespace glint {
namespace {

// One file read three ways: as sRGB colour by two materials, as linear roughness by one.
TEST(GpuScene, PacksOneLayerPerTextureAndEncoding) {
  Scene s;
  s.textures = {{.name = "wood", .path = "wood.png"}};
  s.materials = {{.name = "m", .color_texture = "wood"},
                 {.name = "rough", .roughness_texture = "wood"},
                 {.name = "same", .color_texture = "wood"}};
  s.quads = {{.material = "m", .corners = {glm::vec3{0, 0, 0}, glm::vec3{0, 1, 0},
                                           glm::vec3{1, 0, 0}, glm::vec3{1, 1, 0}}}};
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

// Each texture slot (renderer/texture_slots.h) fills the component of GpuMaterial::layers that
// shaders/lib/trace_scene_tables.glsl reads it from (x colour, y emission, z roughness), decoded as the
// shader expects (colour and emission sRGB, roughness linear).
TEST(GpuScene, EachTextureSlotFillsTheLayerTheShaderReadsItFrom) {
  struct Expected {
    std::string Material::*member;
    int component;
    ColorEncoding encoding;
  };
  for (const Expected& e : {Expected{&Material::color_texture, 0, ColorEncoding::srgb},
                            Expected{&Material::emission_texture, 1, ColorEncoding::srgb},
                            Expected{&Material::roughness_texture, 2, ColorEncoding::linear}}) {
    Scene s;
    s.textures = {{.name = "wood", .path = "wood.png"}};
    Material m{.name = "m"};
    m.*e.member = "wood";
    s.materials = {m};
    const PackedScene p = pack_scene(s);
    ASSERT_EQ(p.layers.size(), 1u) << e.component;
    EXPECT_EQ(p.layers[0].encoding, e.encoding) << e.component;
    for (int c = 0; c < 4; ++c) EXPECT_EQ(p.materials[0].layers[c], c == e.component ? 0 : -1) << e.component;
  }
}

}  // namespace
}  // namespace glint
