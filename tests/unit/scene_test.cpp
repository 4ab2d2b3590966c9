#include <gtest/gtest.h>

#include "renderer/scene.h"

namespace glint {

TEST(Scene, FindsMaterialsAndTexturesByName) {
  Scene scene;
  scene.materials.push_back({.name = "a"});
  scene.materials.push_back({.name = "b"});
  scene.textures.push_back({.name = "wood", .path = "wood.png"});
  EXPECT_EQ(find_material(scene, "b"), 1);
  EXPECT_EQ(find_material(scene, "c"), -1);
  EXPECT_EQ(find_texture(scene, "wood"), 0);
}

TEST(Scene, NamesRoundTripThroughStrings) {
  for (auto t : {MaterialType::matte, MaterialType::reflective, MaterialType::glossy,
                 MaterialType::transparent})
    EXPECT_EQ(material_type_from_string(to_string(t)), t);
  EXPECT_FALSE(material_type_from_string("metal").has_value());
  EXPECT_EQ(tonemap_from_string("linear"), Tonemap::linear);
  EXPECT_FALSE(tonemap_from_string("aces").has_value());
}

TEST(Scene, ResolvesRelativeAssetPathsAgainstTheProjectFolder) {
  Scene scene;
  scene.base_dir = "/projects/demo";
  EXPECT_EQ(resolve_asset_path(scene, "assets/wood.png"), "/projects/demo/assets/wood.png");
  EXPECT_EQ(resolve_asset_path(scene, "/abs/sky.hdr"), "/abs/sky.hdr");
}

}  // namespace glint
