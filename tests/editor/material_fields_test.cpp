// The per-type field table of the material panel against the renderer's material types.
#include <gtest/gtest.h>

#include "editor/material_fields.h"
#include "renderer/scene_fields.h"

namespace glint {
namespace {

TEST(MaterialFields, EveryTypeOfTheProjectFileHasOneEntry) {
  // A type added to the file format without a row here fails: the panel would not know it.
  for (MaterialType t : EnumNames<MaterialType>::values) {
    const MaterialTypeInfo* info = material_type_info(t);
    ASSERT_NE(info, nullptr) << to_string(t);
    EXPECT_STREQ(info->name, to_string(t));
    EXPECT_NE(info->fields & kFieldColour, 0u) << to_string(t);
  }
  EXPECT_EQ(std::size(kMaterialTypes), EnumNames<MaterialType>::values.size());
}

TEST(MaterialFields, OnlyTheFieldsATypeReads) {
  // shaders/lib/bsdf.glsl: matte reads neither roughness nor ior; reflective (a conductor
  // through Schlick with the colour as F0) no ior; glossy and transparent both.
  EXPECT_FALSE(uses_field(MaterialType::matte, kFieldRoughness));
  EXPECT_FALSE(uses_field(MaterialType::matte, kFieldIor));
  EXPECT_TRUE(uses_field(MaterialType::reflective, kFieldRoughness));
  EXPECT_FALSE(uses_field(MaterialType::reflective, kFieldIor));
  EXPECT_TRUE(uses_field(MaterialType::glossy, kFieldIor));
  EXPECT_TRUE(uses_field(MaterialType::transparent, kFieldIor));
  for (const MaterialTypeInfo& t : kMaterialTypes) {  // every type emits and has coverage
    EXPECT_TRUE(uses_field(t.type, kFieldEmission)) << t.name;
    EXPECT_TRUE(uses_field(t.type, kFieldOpacity)) << t.name;
  }
}

}  // namespace
}  // namespace glint
