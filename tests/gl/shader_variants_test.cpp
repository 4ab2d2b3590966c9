// Programs specialised to a scene's ShaderFeatures: the same image as the generic
// program with the same seed, and the switch from generic to specialised without waiting.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "renderer/bvh.h"
#include "renderer/loop_shapes.h"
#include "renderer/project_file.h"
#include "tests/gl/gl_test_support.h"

namespace glint {
namespace {

// Both programs run the same GLSL statements on the same random numbers: removed branches are
// ones the scene never takes, and no removal skips a rand() call. What may still differ is the
// compiler's instruction selection around the removed code (e.g. a multiply-add fused in one
// program and not the other): float rounding at 1 ulp per operation, which the comparison allows
// relative to the pixel (1e-4, i.e. ~800 ulp over a path of a few hundred operations).
// A sample whose path such a rounding sends to another surface would exceed it; with 32x32
// pixels and 4 spp none does here, so a failure means the programs really differ.
constexpr double kRelativeTolerance = 1e-4;


Image render(const Scene& scene, int w, int h, bool generic, int passes, bool* all_specialised,
             SamplerKind sampler = RenderOptions{}.sampler) {
  GpuRendererOptions options;
  options.force_generic_shader = generic;
  GpuRenderer r(options);
  RenderOptions estimator;
  estimator.sampler = sampler;
  r.set_options(estimator);
  r.sync(scene, w, h);
  // The program keeps only the sampler in use.
  EXPECT_NE(shader_defines(r.features()).find(sampler == SamplerKind::sobol ? "GLINT_NO_PCG_SAMPLER" : "GLINT_NO_SOBOL_SAMPLER"),
            std::string::npos);
  if (!generic) r.prepare_specialised_program();
  bool specialised = true;
  for (int i = 0; i < passes; ++i) {
    r.trace(2);
    specialised = specialised && !r.last_pass_generic();
  }
  if (all_specialised) *all_specialised = specialised;
  return r.read_accumulation();
}

TEST(GlShaderVariants, EveryProjectRendersTheSameSpecialisedAndGeneric) {
  test::ensure_gl_context();
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(GLINT_SOURCE_DIR "/projects")) {
    if (entry.path().extension() != ".glint") continue;
    SCOPED_TRACE(entry.path().filename().string());
    Scene scene = load_project(entry.path());
    scene.render.seed = 7;
    const int w = 32, h = std::max(1, 32 * scene.film.height / scene.film.width);
    bool specialised = false;
    Image special = render(scene, w, h, false, 2, &specialised);
    Image generic = render(scene, w, h, true, 2, nullptr);
    // The renderer keeps only the traversal it uses (loop or BVH, renderer/bvh.h), so every
    // scene lacks a feature of the generic program.
    ShaderFeatures needed = scene_features(scene);
    needed.bvh_traversal = use_bvh(Accel::automatic, static_cast<long>(scene.spheres.size() + scene.quads.size()),
                                   scene.render.max_bounces);
    needed.loop_traversal = !needed.bvh_traversal;
    needed = with_loop_counts(needed, static_cast<long>(scene.spheres.size()), static_cast<long>(scene.quads.size()));
    EXPECT_EQ(specialised, shader_defines(needed) != "")
        << "every pass should use the specialised program when the scene lacks a feature";
    double diff = test::max_relative_difference(special, generic);
    EXPECT_LE(diff, kRelativeTolerance);
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", diff);
    RecordProperty(entry.path().stem().string() + "_max_relative_difference", text);
    ++count;
  }
  EXPECT_GE(count, 6);
}

// Scenes that no example project is: each leaves out code the projects keep (next-event
// estimation entirely, the environment branch of it, one shape kind), or keeps code they leave
// out (the shadow ray of an opaque scene with textured emitters).
TEST(GlShaderVariants, DerivedScenesRenderTheSameSpecialisedAndGeneric) {
  test::ensure_gl_context();
  struct Case {
    const char* name;
    const char* defines;  // that the specialised program must have
    Scene scene;
  };
  std::vector<Case> cases;
  Scene base = load_project(GLINT_SOURCE_DIR "/projects/cornell_box.glint");
  base.render.seed = 11;
  {
    Scene s = base;  // lit only by the constant environment: nothing for shadow rays to aim at
    for (Material& m : s.materials) m.emission = glm::vec3(0);
    s.environment.color = glm::vec3(0.4f, 0.45f, 0.5f);
    s.environment.intensity = 1;
    cases.push_back({"no emitters", "GLINT_NO_EMITTERS", s});
    s.quads.clear();
    s.spheres.push_back({.name = "floor", .center = {0, -1000.5f, 0}, .radius = 1000, .material = s.spheres[0].material});
    cases.push_back({"spheres only", "GLINT_NO_QUADS", s});
  }
  {
    Scene s = base;  // the quad light, walls and no spheres
    s.spheres.clear();
    cases.push_back({"quads only", "GLINT_NO_SPHERES", s});
  }
  {
    Scene s = base;  // the glossy ball made of rough glass, the mirror ball of smooth glass
    s.materials.push_back({.name = "glass", .type = MaterialType::refractive, .color = {1, 1, 1}});
    s.materials.push_back({.name = "rough_glass", .type = MaterialType::refractive, .color = {1, 1, 1},
                           .roughness = 0.3f});
    s.spheres[0].material = "glass";
    s.spheres[1].material = "rough_glass";
    cases.push_back({"refractive", "GLINT_NO_GLOSSY", s});
  }
  {
    Scene s = base;  // opaque but textured: shadow rays find the light's textured emission
    s.textures.push_back({.name = "wood", .path = "assets/wood_color.png"});
    s.materials[0].color_texture = "wood";
    for (Material& m : s.materials) {
      if (m.emission != glm::vec3(0)) m.emission_texture = "wood";
    }
    EXPECT_TRUE(scene_features(s).has_textures);
    cases.push_back({"textured, opaque", "GLINT_NO_COVERAGE", s});
  }
  for (const Case& c : cases) for (SamplerKind sampler : {SamplerKind::pcg, SamplerKind::sobol}) {
    SCOPED_TRACE(std::string(c.name) + (sampler == SamplerKind::sobol ? ", sobol" : ", pcg"));
    bool specialised = false;
    Image special = render(c.scene, 24, 24, false, 2, &specialised, sampler);
    Image generic = render(c.scene, 24, 24, true, 2, nullptr, sampler);
    EXPECT_TRUE(specialised);
    EXPECT_NE(shader_defines(scene_features(c.scene)).find(c.defines), std::string::npos);
    double mean = 0;
    for (float v : special.pixels) mean += v;
    EXPECT_GT(mean, 0.0) << "the scene is lit";
    EXPECT_LE(test::max_relative_difference(special, generic), kRelativeTolerance);
  }
}

// A scene of few shapes gets a program for its exact numbers of spheres and quads, with the
// closest-hit loop unrolled and the shapes in a uniform block (renderer/loop_shapes.h): the
// same image as the generic program after shapes move (same program, new block), and at the
// limit of kLoopShapesMax spheres, one past which the loop reads the tables again.
TEST(GlShaderVariants, UnrolledLoopFollowsMovedShapesAndStopsAtItsLimit) {
  test::ensure_gl_context();
  Scene scene = load_project(GLINT_SOURCE_DIR "/projects/cornell_box.glint");
  scene.render.seed = 5;
  GpuRenderer r;
  r.sync(scene, 24, 24);
  r.prepare_specialised_program();
  r.trace(2);
  ASSERT_FALSE(r.last_pass_generic());
  const std::string defines = r.last_pass_defines();
  EXPECT_NE(defines.find("#define GLINT_LOOP_SPHERES 2\n#define GLINT_LOOP_QUADS 6\n"), std::string::npos)
      << defines;
  scene.spheres[0].center += glm::vec3(30, 10, -20);
  scene.spheres[1].radius *= 0.8f;
  for (glm::vec3& corner : scene.quads.back().corners) corner.y -= 20;  // the light
  ASSERT_TRUE(r.sync(scene, 24, 24).accumulation_reset);
  r.trace(2);
  EXPECT_EQ(r.last_pass_defines(), defines) << "moving shapes keeps the program";
  GpuRendererOptions generic;
  generic.force_generic_shader = true;
  GpuRenderer g(generic);
  g.sync(scene, 24, 24);
  g.trace(2);
  EXPECT_LE(test::max_relative_difference(r.read_accumulation(), g.read_accumulation()), kRelativeTolerance)
      << "the block holds the moved shapes";

  // kLoopShapesMax small balls in a row under the Cornell box's light (47 shapes in all: still
  // traced by the loop), then one more.
  Scene many = load_project(GLINT_SOURCE_DIR "/projects/cornell_box.glint");
  many.render.seed = 9;
  many.spheres.clear();
  for (int i = 0; i < kLoopShapesMax; ++i)
    many.spheres.push_back({.name = "b" + std::to_string(i), .center = {40.0f + 15.0f * i, 10, 250},
                            .radius = 7, .material = scene.spheres[0].material});
  for (int extra = 0; extra < 2; ++extra) {
    SCOPED_TRACE(extra ? "one sphere past the limit" : "at the limit");
    if (extra) many.spheres.push_back({.name = "last", .center = {278, 100, 278}, .radius = 60,
                                       .material = scene.spheres[0].material});
    ASSERT_FALSE(use_bvh(Accel::automatic, static_cast<long>(many.spheres.size() + many.quads.size()),
                         many.render.max_bounces));
    GpuRenderer special;
    special.sync(many, 24, 24);
    special.prepare_specialised_program();
    special.trace(2);
    EXPECT_FALSE(special.last_pass_generic());
    EXPECT_EQ(special.last_pass_defines().find("GLINT_LOOP_SPHERES") != std::string::npos, extra == 0)
        << special.last_pass_defines();
    GpuRenderer plain(generic);
    plain.sync(many, 24, 24);
    plain.trace(2);
    EXPECT_LE(test::max_relative_difference(special.read_accumulation(), plain.read_accumulation()),
              kRelativeTolerance);
  }
}

// Traces single-sample passes until the specialised program runs (or 30 s pass); returns how
// many passes used the generic one.
int passes_until_specialised(GpuRenderer& r) {
  auto start = std::chrono::steady_clock::now();
  int generic_passes = 0;
  for (;;) {
    r.trace(1);
    if (!r.last_pass_generic()) return generic_passes;
    ++generic_passes;
    if (std::chrono::steady_clock::now() - start > std::chrono::seconds(30)) return -1;
  }
}

Scene cornell() {
  Scene s = load_project(GLINT_SOURCE_DIR "/projects/cornell_box.glint");
  s.render.seed = 3;
  return s;
}

TEST(GlShaderVariants, SwitchesToTheSpecialisedProgramWhenItIsReady) {
  test::ensure_gl_context();
  Scene scene = cornell();
  GpuRenderer r;
  r.sync(scene, 16, 16);
  int generic_passes = passes_until_specialised(r);
  // The first pass never waits for a compile: it runs the generic program and issues the
  // specialised compile afterwards.
  EXPECT_GE(generic_passes, 1);
  ASSERT_GT(generic_passes, 0) << "never switched";
  EXPECT_EQ(r.last_pass_defines(), shader_defines(r.features()));
  // Mixed passes, same image as the generic program alone.
  r.trace(2);
  GpuRendererOptions generic;
  generic.force_generic_shader = true;
  GpuRenderer g(generic);
  g.sync(scene, 16, 16);
  for (int64_t i = 0; i < r.sample_count() - 2; ++i) g.trace(1);
  g.trace(2);
  EXPECT_TRUE(g.last_pass_generic());
  EXPECT_LE(test::max_relative_difference(r.read_accumulation(), g.read_accumulation()), kRelativeTolerance);
}

TEST(GlShaderVariants, StructuralEditFallsBackToGenericUntilItsVariantIsReady) {
  test::ensure_gl_context();
  Scene scene = cornell();
  GpuRenderer r;
  r.sync(scene, 16, 16);
  ASSERT_GT(passes_until_specialised(r), 0);
  const std::string before = r.last_pass_defines();
  EXPECT_NE(before.find("GLINT_NO_TEXTURES"), std::string::npos);

  // Structural edit: the white material gets a colour texture.
  scene.textures.push_back({.name = "wood", .path = "assets/wood_color.png"});
  scene.materials[0].color_texture = "wood";
  ASSERT_TRUE(r.sync(scene, 16, 16).accumulation_reset);
  EXPECT_TRUE(r.features().has_textures);
  r.trace(1);
  EXPECT_TRUE(r.last_pass_generic()) << "the old variant has no texture fetch";
  GpuRendererOptions generic;
  generic.force_generic_shader = true;
  GpuRenderer g(generic);
  g.sync(scene, 16, 16);
  g.trace(1);
  EXPECT_LE(test::max_relative_difference(r.read_accumulation(), g.read_accumulation()), kRelativeTolerance)
      << "the image while the new variant compiles";
  EXPECT_GE(passes_until_specialised(r), 0);
  EXPECT_EQ(r.last_pass_defines().find("GLINT_NO_TEXTURES"), std::string::npos);

  // Undoing the edit needs fewer features: the cached first variant is used at once.
  scene.materials[0].color_texture.clear();
  r.sync(scene, 16, 16);
  r.trace(1);
  EXPECT_EQ(r.last_pass_defines(), before);
}

TEST(GlShaderVariants, ForcedGenericNeverSpecialises) {
  test::ensure_gl_context();
  GpuRendererOptions options;
  options.force_generic_shader = true;
  GpuRenderer r(options);
  r.sync(cornell(), 8, 8);
  r.prepare_specialised_program();
  for (int i = 0; i < 3; ++i) {
    r.trace(1);
    EXPECT_TRUE(r.last_pass_generic());
  }
}

}  // namespace
}  // namespace glint
