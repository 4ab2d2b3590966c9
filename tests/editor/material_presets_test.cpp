// Material presets (editor/material_presets.h): the table's constants, applying one, and the
// properties panel's Preset combo driven with the mouse as one undo step.
#include <gtest/gtest.h>

#include <string_view>

#include "editor/material_presets.h"
#include "editor/scene_edits.h"
#include "editor/ui_layout.h"
#include "editor_test_util.h"
#include "ui_test_fixture.h"

namespace glint {
namespace {

using test::UiTest;

const MaterialPreset& preset(std::string_view name) {
  for (const MaterialPreset& p : kMaterialPresets)
    if (name == p.name) return p;
  ADD_FAILURE() << "no preset " << name;
  return kMaterialPresets[0];
}

TEST(MaterialPresets, RealConstants) {
  EXPECT_EQ(preset("Glass").ior, 1.5f);
  EXPECT_EQ(preset("Water").ior, 1.33f);
  EXPECT_EQ(preset("Diamond").ior, 2.42f);
  for (const char* dielectric : {"Glass", "Water", "Diamond"}) EXPECT_EQ(preset(dielectric).type, MaterialType::refractive);
  // Metals: mirrors or rough mirrors with their measured normal-incidence reflectance.
  EXPECT_EQ(preset("Gold").colour, glm::vec3(1.000f, 0.766f, 0.336f));
  EXPECT_EQ(preset("Silver").colour, glm::vec3(0.972f, 0.960f, 0.915f));
  EXPECT_EQ(preset("Copper").colour, glm::vec3(0.955f, 0.637f, 0.538f));
  EXPECT_EQ(preset("Aluminium").colour, glm::vec3(0.913f, 0.921f, 0.925f));
  for (const char* metal : {"Gold", "Silver", "Copper", "Aluminium"}) EXPECT_EQ(preset(metal).type, MaterialType::reflective);
  EXPECT_FALSE(preset("Plastic").sets_colour);
  EXPECT_FALSE(preset("Rubber").sets_colour);
  EXPECT_GT(preset("Rubber").roughness, preset("Plastic").roughness);
}

TEST(MaterialPresets, EveryPresetGivesAValidMaterialThatMatchesIt) {
  Scene s = new_scene();
  s.textures.push_back({"wood", "wood.png"});
  for (const MaterialPreset& p : kMaterialPresets) {
    SCOPED_TRACE(p.name);
    Material& m = s.materials[0];
    m.color_texture = "wood";
    m.emission = {0.5f, 0, 0};
    m.opacity = 0.5f;
    apply_material_preset(m, p);
    EXPECT_EQ(m.type, p.type);
    EXPECT_EQ(m.roughness, p.roughness);
    EXPECT_EQ(m.ior, p.ior);
    EXPECT_EQ(m.color_texture.empty(), p.sets_colour);  // a measured colour replaces the texture
    EXPECT_EQ(m.emission, glm::vec3(0.5f, 0, 0));     // kept
    EXPECT_EQ(m.opacity, 0.5f);
    EXPECT_EQ(matching_preset(m), &p);
    EXPECT_EQ(test::problems(s), "");
  }
  s.materials[0].roughness = 0.123f;
  EXPECT_EQ(matching_preset(s.materials[0]), nullptr);
}

class MaterialPresetsUiTest : public UiTest {
 protected:
  // The centre of the widget `label` of window `window` (found by hovering down it).
  ImVec2 find(const char* window, const char* label) {
    ImGuiWindow* w = ImGui::FindWindowByName(window);
    if (!w) return ImVec2(-1, -1);
    const ImGuiID id = w->GetID(label);
    for (float x : {w->Pos.x + 30, w->Pos.x + 80})
      for (float y = w->Pos.y + 2; y < w->Pos.y + w->Size.y; y += 4) {
        mouse_to(ImVec2(x, y));
        frame();
        if (ImGui::GetCurrentContext()->HoveredId == id) return ImVec2(x, y);
      }
    return ImVec2(-1, -1);
  }
};

TEST_F(MaterialPresetsUiTest, ChoosingGoldIsOneUndoStep) {
  ImGui::GetIO().DisplaySize = ImVec2(1000, 800);
  doc_.selection = {SelectionKind::material, 0};
  frame();
  frame();
  const Material before = doc_.scene.materials[0];
  const ImVec2 combo = find(kPropertiesWindow, "Preset");
  ASSERT_GE(combo.x, 0) << "no Preset combo";
  click(combo);
  ImGuiWindow* popup = ImGui::FindWindowByName("##Combo_00");
  ASSERT_TRUE(popup && popup->Active) << "the Preset combo did not open";
  const ImVec2 gold = find("##Combo_00", "Gold");
  ASSERT_GE(gold.x, 0) << "no Gold in the Preset combo";
  click(gold);
  const Material& m = doc_.scene.materials[0];
  EXPECT_EQ(m.type, MaterialType::reflective);
  EXPECT_EQ(m.color, glm::vec3(1.000f, 0.766f, 0.336f));
  EXPECT_EQ(m.name, before.name);
  press(GLFW_KEY_Z, /*ctrl=*/true);
  EXPECT_EQ(doc_.scene.materials[0], before);
}

}  // namespace
}  // namespace glint
