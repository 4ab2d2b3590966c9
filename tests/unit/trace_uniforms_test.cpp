// The trace pass's scene uniforms (renderer/trace_uniforms.h) computed without GL: the camera
// relative to the render origin, which lights shadow rays go to, the options that become
// uniforms, and how passes are split into draws.
#include <gtest/gtest.h>

#include "renderer/bvh.h"
#include "renderer/loop_budget.h"
#include "renderer/trace_uniforms.h"

namespace glint {
namespace {

Scene scene_with_camera_at(glm::vec3 position) {
  Scene s;
  s.camera.position = position;
  s.camera.target = position + glm::vec3(0, 0, -1);
  s.render.max_bounces = 6;
  s.render.seed = 7;
  return s;
}

TEST(TraceUniforms, CameraIsRelativeToTheRenderOriginAndTheFilmsAspect) {
  const Scene scene = scene_with_camera_at({1000.5f, 2, -3});
  TraceUniforms u;
  FrameInputs in;
  in.origin = glm::dvec3(1000, 0, 0);
  in.width = 200;
  in.height = 100;
  set_frame_uniforms(u, scene, RenderOptions{}, in);
  EXPECT_EQ(u.cam_origin, glm::vec3(0.5f, 2, -3));
  EXPECT_FLOAT_EQ(u.cam_aspect, 2.0f);
  EXPECT_NEAR(u.cam_forward.z, -1.0f, 1e-6f);
  EXPECT_EQ(u.max_bounces, 6);
  EXPECT_EQ(u.seed, 7u);
  in.height = 0;  // an empty film keeps a square camera
  set_frame_uniforms(u, scene, RenderOptions{}, in);
  EXPECT_FLOAT_EQ(u.cam_aspect, 1.0f);
}

// Shadow rays: to the emitters, to a textured environment half of the time beside them and
// always without them; a constant environment is left to BSDF sampling; off without light
// sampling (emitters) or environment sampling (the map).
TEST(TraceUniforms, ShadowRaysGoWhereTheOptionsAndTheScenePermit) {
  Scene scene = scene_with_camera_at({0, 0, 5});
  TraceUniforms u;
  FrameInputs in;
  in.light_count = 3;
  RenderOptions options;
  set_frame_uniforms(u, scene, options, in);
  EXPECT_EQ(u.light_count, 3);
  EXPECT_EQ(u.env_select, 0.0f) << "constant environment";
  EXPECT_EQ(u.env_textured, 0);
  EXPECT_EQ(u.env_color, scene.environment.color);
  scene.environment.texture = "sky.hdr";
  scene.environment.intensity = 2;
  set_frame_uniforms(u, scene, options, in);
  EXPECT_EQ(u.env_select, 0.5f);
  EXPECT_EQ(u.env_color, glm::vec3(2));
  options.light_sampling = false;
  set_frame_uniforms(u, scene, options, in);
  EXPECT_EQ(u.light_count, 0);
  EXPECT_EQ(u.env_select, 1.0f);
  options.environment_sampling = false;
  set_frame_uniforms(u, scene, options, in);
  EXPECT_EQ(u.env_select, 0.0f);
}

TEST(TraceUniforms, OptionsAndTraversal) {
  const Scene scene = scene_with_camera_at({0, 0, 5});
  TraceUniforms u;
  u.sphere_count = 5;  // the uploads' uniforms are kept
  u.env_distribution_size = {8, 4};
  RenderOptions options;
  options.sampler = SamplerKind::pcg;
  options.russian_roulette = false;
  options.clamp = 10;
  options.first_sample = 64;
  FrameInputs in;
  in.use_bvh = true;
  in.llvmpipe = false;
  set_frame_uniforms(u, scene, options, in);
  EXPECT_EQ(u.sobol, 0);
  EXPECT_EQ(u.russian_roulette, 0);
  EXPECT_EQ(u.clamp, 10.0f);
  EXPECT_EQ(u.first_sample, 64u);
  EXPECT_EQ(u.use_bvh, 1);
  EXPECT_EQ(u.bvh_max_steps, kMaxBvhSteps) << "the generous bound off llvmpipe";
  in.llvmpipe = true;
  set_frame_uniforms(u, scene, options, in);
  EXPECT_EQ(u.bvh_max_steps, bvh_max_steps(kBvhMaxLeafSize, 6)) << "llvmpipe's loop limit";
  EXPECT_EQ(u.sphere_count, 5);
  EXPECT_EQ(u.env_distribution_size, glm::ivec2(8, 4));
}

TEST(TraceUniforms, DrawSplitFollowsTheLoopBudget) {
  const DrawSplit few = draw_split(4, 6, false);
  EXPECT_EQ(few.samples_per_draw, samples_per_draw_for(loop_iterations_per_sample(4, 6)));
  EXPECT_FALSE(few.exceeds_loop_limit);
  const DrawSplit many = draw_split(100000, 6, false);
  EXPECT_EQ(many.samples_per_draw, 1);
  EXPECT_TRUE(many.exceeds_loop_limit);
  const DrawSplit bvh = draw_split(100000, 6, true);
  EXPECT_FALSE(bvh.exceeds_loop_limit) << "the BVH's step cap keeps a sample within the limit";
}

}  // namespace
}  // namespace glint
