// The material types' table (renderer/material_types.h): one row per type of the project file,
// names that round-trip, the shader's codes as the table says, and the fields each type reads.
#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <string>

#include "renderer/material_types.h"
#include "renderer/scene_fields.h"
#include "renderer/shader_sources.h"

namespace glint {
namespace {

TEST(MaterialTypes, EveryTypeOfTheProjectFileHasOneEntry) {
  for (MaterialType t : EnumNames<MaterialType>::values) {
    const MaterialTypeInfo& info = material_type_info(t);
    EXPECT_EQ(info.type, t);
    EXPECT_STREQ(info.name, to_string(t));
    EXPECT_EQ(material_type_from_string(info.name), t);
    EXPECT_NE(info.fields & kFieldColour, 0u) << to_string(t);
  }
  EXPECT_EQ(std::size(kMaterialTypes), EnumNames<MaterialType>::values.size());
}

TEST(MaterialTypes, OnlyTheFieldsATypeReads) {
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

// The shader compares a material's packed code (its row's index, gpu_scene.cpp) with
// `const int MATERIAL_<NAME> = <code>;` in shaders/lib/bsdf.glsl: each row's constant must
// hold its index, and the shader must declare no type the table lacks.
TEST(MaterialTypes, ShaderCodesMatchTheTable) {
  const std::string source = shader_source("lib/bsdf.glsl");
  const std::regex declaration(R"(const int (MATERIAL_[A-Z_]+) = (\d+);)");
  std::map<std::string, int> codes;
  for (auto it = std::sregex_iterator(source.begin(), source.end(), declaration); it != std::sregex_iterator(); ++it)
    codes[(*it)[1].str()] = std::stoi((*it)[2].str());
  EXPECT_EQ(codes.size(), kMaterialTypeCount);
  for (size_t i = 0; i < kMaterialTypeCount; ++i) {
    const auto code = codes.find(kMaterialTypes[i].shader_code);
    ASSERT_NE(code, codes.end()) << kMaterialTypes[i].shader_code << " is not declared in bsdf.glsl";
    EXPECT_EQ(code->second, static_cast<int>(i)) << kMaterialTypes[i].shader_code;
    EXPECT_NE(source.find(kMaterialTypes[i].omit_define), std::string::npos) << kMaterialTypes[i].omit_define;
  }
}

}  // namespace
}  // namespace glint
