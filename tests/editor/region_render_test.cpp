// Region render and the error map in the viewport (editor/ui_region.cpp), driven with keys and
// the mouse: Ctrl+B and a drag set the region, samples then go there only, Ctrl+Alt+B clears it.
#include <gtest/gtest.h>

#include "ui_test_fixture.h"

namespace glint {
namespace {

using test::UiTest;

class RegionRenderTest : public UiTest {
 protected:
  void press_ctrl_alt_b() {
    ImGuiIO& io = ImGui::GetIO();
    io.AddKeyEvent(ImGuiMod_Ctrl, true);
    io.AddKeyEvent(ImGuiMod_Alt, true);
    io.AddKeyEvent(ImGuiKey_B, true);
    frame();
    io.AddKeyEvent(ImGuiKey_B, false);
    io.AddKeyEvent(ImGuiMod_Alt, false);
    io.AddKeyEvent(ImGuiMod_Ctrl, false);
    frame();
  }
  void drag(ImVec2 from, ImVec2 to) {
    mouse_to(from);
    frame();
    mouse_button(true);
    frame();
    for (int i = 1; i <= 4; ++i) {
      mouse_to(ImVec2(from.x + (to.x - from.x) * i / 4, from.y + (to.y - from.y) * i / 4));
      frame();
    }
    mouse_button(false);
    frame();
  }
  ImVec2 at(float fx, float fy) {
    return ImVec2(state_.viewport.pos.x + fx * state_.viewport.size.x, state_.viewport.pos.y + fy * state_.viewport.size.y);
  }
};

TEST_F(RegionRenderTest, CtrlBAndADragRenderOnlyThereCtrlAltBClears) {
  for (int i = 0; i < 2; ++i) frame();
  const Scene scene_before = doc_.scene;
  press(GLFW_KEY_B, /*ctrl=*/true);
  ASSERT_TRUE(state_.tools.region_tool);
  drag(at(0.25f, 0.3f), at(0.75f, 0.7f));
  EXPECT_FALSE(state_.tools.region_tool);
  ASSERT_TRUE(state_.viewport.region.has_value());
  EXPECT_NEAR(state_.viewport.region->x0, 0.25f, 0.01f);
  EXPECT_NEAR(state_.viewport.region->y1, 0.7f, 0.01f);
  EXPECT_EQ(doc_.scene, scene_before);  // the drag neither orbited nor selected
  EXPECT_EQ(doc_.selection.kind, SelectionKind::none);

  const GpuRenderer& r = viewport_->renderer();
  const std::optional<PixelRect> region = r.sample_region();
  ASSERT_TRUE(region.has_value());
  const float frozen = r.read_variance().at(0, 0)[3];
  const int64_t spp = r.sample_count();
  for (int i = 0; i < 4; ++i) frame();
  ASSERT_GT(r.sample_count(), spp) << "no samples after the region was drawn";
  const Image counts = r.read_variance();
  EXPECT_EQ(counts.at(region->x0, region->y0)[3], float(r.sample_count()));
  EXPECT_EQ(counts.at(region->x1 - 1, region->y1 - 1)[3], float(r.sample_count()));
  EXPECT_EQ(counts.at(0, 0)[3], frozen);  // outside: no samples since the region was drawn
  EXPECT_EQ(counts.at(r.width() - 1, r.height() - 1)[3], frozen);
  EXPECT_LT(frozen, float(r.sample_count()));

  state_.viewport.error_map = true;
  frame();
  EXPECT_NE(state_.viewport.frame.error_map_texture, 0u);

  press_ctrl_alt_b();
  EXPECT_FALSE(state_.viewport.region.has_value());
  frame();
  EXPECT_FALSE(viewport_->renderer().sample_region().has_value());
  const Image after = viewport_->renderer().read_variance();
  EXPECT_GT(after.at(0, 0)[3], frozen);  // every pixel samples again
}

}  // namespace
}  // namespace glint
