// ShaderFeatures of scenes: what a scene needs decides which `#define GLINT_NO_...` lines the
// trace shader gets (renderer/shader_features.h).
#include <gtest/gtest.h>

#include <array>
#include <random>

#include "renderer/loop_shapes.h"
#include "renderer/project_file.h"
#include "renderer/quad_shape.h"
#include "renderer/shader_features.h"

namespace glint {
namespace {

uint32_t bit(MaterialType t) { return 1u << static_cast<int>(t); }

Scene one_sphere(Material m) {
  Scene s;
  m.name = "m";
  s.materials.push_back(m);
  s.spheres.push_back({.name = "ball", .material = "m"});
  return s;
}

TEST(ShaderFeatures, GenericHasEverythingAndNoDefines) {
  ShaderFeatures g = generic_features();
  EXPECT_TRUE(g.has_emitters && g.has_textures && g.env_textured && g.thin_lens && g.has_coverage);
  EXPECT_EQ(g.material_types, 0x1Fu);
  EXPECT_EQ(shader_defines(g), "");
}

TEST(ShaderFeatures, EmptySceneNeedsNothing) {
  Scene s;
  s.camera.aperture_radius = 0;
  ShaderFeatures f = scene_features(s);
  EXPECT_FALSE(f.has_emitters || f.has_textures || f.env_textured || f.thin_lens || f.has_coverage ||
               f.has_spheres || f.has_quads);
  EXPECT_EQ(f.material_types, 0u);
  EXPECT_EQ(shader_defines(f),
            "#define GLINT_NO_EMITTERS\n#define GLINT_NO_TEXTURES\n#define GLINT_NO_ENV_TEXTURE\n"
            "#define GLINT_NO_THIN_LENS\n#define GLINT_NO_COVERAGE\n#define GLINT_NO_MATTE\n"
            "#define GLINT_NO_REFLECTIVE\n#define GLINT_NO_GLOSSY\n#define GLINT_NO_TRANSPARENT\n"
            "#define GLINT_NO_REFRACTIVE\n#define GLINT_NO_SPHERES\n#define GLINT_NO_QUADS\n"
            "#define GLINT_NO_GENERAL_QUADS\n#define GLINT_NO_GENERAL_QUAD_LIGHTS\n");
}

TEST(ShaderFeatures, CornellBox) {
  ShaderFeatures f = scene_features(load_project(GLINT_SOURCE_DIR "/projects/cornell_box.glint"));
  EXPECT_TRUE(f.has_emitters);
  EXPECT_FALSE(f.has_textures);
  EXPECT_FALSE(f.env_textured);
  EXPECT_FALSE(f.thin_lens);
  EXPECT_FALSE(f.has_coverage);
  EXPECT_TRUE(f.has_spheres && f.has_quads);
  EXPECT_EQ(f.material_types, bit(MaterialType::matte) | bit(MaterialType::reflective) |
                                  bit(MaterialType::glossy));
  EXPECT_EQ(shader_defines(f),
            "#define GLINT_NO_TEXTURES\n#define GLINT_NO_ENV_TEXTURE\n#define GLINT_NO_THIN_LENS\n"
            "#define GLINT_NO_COVERAGE\n#define GLINT_NO_TRANSPARENT\n#define GLINT_NO_REFRACTIVE\n"
            "#define GLINT_NO_GENERAL_QUADS\n#define GLINT_NO_GENERAL_QUAD_LIGHTS\n"
            "#define GLINT_MNEE\n");  // its mirror ball casts caustics of the ceiling lamp
}

TEST(ShaderFeatures, DefaultProjectNeedsEverything) {
  // Emissive lamp, textures, sky, aperture 0.03, a checker with alpha on the cut-out panel, and
  // the four material types other than refractive.
  ShaderFeatures f = scene_features(load_project(GLINT_SOURCE_DIR "/projects/default.glint"));
  ShaderFeatures expected = generic_features();
  expected.material_types &= ~bit(MaterialType::refractive);
  expected.has_general_quads = false;        // its quads are rectangles,
  expected.has_general_quad_lights = false;  // its lamp too
  expected.mnee = true;                      // and its smooth mirror ball casts caustics
  EXPECT_EQ(f, expected);
}

TEST(ShaderFeatures, TexturedSpheresHaveOpaqueTexturesOnly) {
  ShaderFeatures f = scene_features(load_project(GLINT_SOURCE_DIR "/projects/textured_spheres.glint"));
  EXPECT_TRUE(f.has_textures);
  EXPECT_TRUE(f.env_textured);
  EXPECT_FALSE(f.has_emitters);
  EXPECT_FALSE(f.has_coverage) << "the colour textures are RGB: coverage is 1 everywhere";
  EXPECT_EQ(f.material_types, bit(MaterialType::reflective) | bit(MaterialType::glossy));
}

TEST(ShaderFeatures, OnlyMaterialsOfPrimitivesCount) {
  Scene s = one_sphere({.type = MaterialType::matte});
  s.materials.push_back({.name = "unused", .type = MaterialType::transparent, .color_texture = "t",
                         .emission = {1, 1, 1}, .opacity = 0.5f});
  s.textures.push_back({.name = "t", .path = "t.png"});
  ShaderFeatures f = scene_features(s);
  EXPECT_EQ(f.material_types, bit(MaterialType::matte));
  EXPECT_FALSE(f.has_emitters || f.has_textures || f.has_coverage);
}

TEST(ShaderFeatures, EmissionCountsOnlyWhenNonZero) {
  // emission * texture: a texture on zero emission adds nothing, so it needs neither feature.
  Scene s = one_sphere({.emission_texture = "t"});
  s.textures.push_back({.name = "t", .path = "t.png"});
  EXPECT_FALSE(scene_features(s).has_emitters);
  EXPECT_FALSE(scene_features(s).has_textures);
  s.materials[0].emission = {0, 0, 0.1f};
  EXPECT_TRUE(scene_features(s).has_emitters);
  EXPECT_TRUE(scene_features(s).has_textures);
}

TEST(ShaderFeatures, CoverageFromOpacityOrAnUnknownTexture) {
  Scene s = one_sphere({.opacity = 0.99f});
  EXPECT_TRUE(scene_features(s).has_coverage);
  s.materials[0].opacity = 1;
  EXPECT_FALSE(scene_features(s).has_coverage);
  // A texture that cannot be probed might have alpha: keep the coverage test.
  s.materials[0].color_texture = "missing";
  s.textures.push_back({.name = "missing", .path = "/no/such/file.png"});
  EXPECT_TRUE(scene_features(s).has_coverage);
  EXPECT_TRUE(scene_features(s).has_textures);
}

TEST(ShaderFeatures, LensAndEnvironment) {
  Scene s = one_sphere({});
  s.camera.aperture_radius = 0.01f;
  s.environment.texture = "sky.hdr";
  ShaderFeatures f = scene_features(s);
  EXPECT_TRUE(f.thin_lens);
  EXPECT_TRUE(f.env_textured);
}

TEST(ShaderFeatures, CoversMeansEveryNeededFeatureIsCompiledIn) {
  ShaderFeatures needed = scene_features(one_sphere({.type = MaterialType::glossy}));
  EXPECT_TRUE(covers(generic_features(), needed));
  EXPECT_TRUE(covers(needed, needed));
  ShaderFeatures more = needed;
  more.has_textures = true;
  EXPECT_TRUE(covers(more, needed));
  EXPECT_FALSE(covers(needed, more));
  ShaderFeatures other_type = needed;
  other_type.material_types = bit(MaterialType::matte);
  EXPECT_FALSE(covers(other_type, needed));
}

TEST(ShaderFeatures, ShapeKinds) {
  Scene s;
  s.materials.push_back(Material{});
  s.spheres.push_back(Sphere{});
  ShaderFeatures spheres_only = scene_features(s);
  EXPECT_TRUE(spheres_only.has_spheres);
  EXPECT_FALSE(spheres_only.has_quads);
  EXPECT_NE(shader_defines(spheres_only).find("#define GLINT_NO_QUADS\n"), std::string::npos);
  EXPECT_EQ(shader_defines(spheres_only).find("GLINT_NO_SPHERES"), std::string::npos);
  s.spheres.clear();
  s.quads.push_back(Quad{});
  ShaderFeatures quads_only = scene_features(s);
  EXPECT_FALSE(quads_only.has_spheres);
  EXPECT_TRUE(quads_only.has_quads);
  EXPECT_FALSE(covers(spheres_only, quads_only));
  EXPECT_FALSE(covers(quads_only, spheres_only));
  EXPECT_TRUE(covers(generic_features(), quads_only));
}

// Which quads the cheaper planar test may take (renderer/quad_shape.h), and the feature.
TEST(ShaderFeatures, PlanarConvexQuads) {
  using C = std::array<glm::vec3, 4>;
  const C rectangle = {glm::vec3(0, 0, 0), glm::vec3(0, 0, 2), glm::vec3(3, 0, 0), glm::vec3(3, 0, 2)};
  EXPECT_TRUE(quad_is_planar_convex(rectangle));
  C trapezoid = rectangle;
  trapezoid[3] = glm::vec3(2, 0, 2);
  EXPECT_TRUE(quad_is_planar_convex(trapezoid));
  C folded = rectangle;
  folded[3].y = 1e-4f;  // 3e-5 of the extent (sqrt(13)) off the plane
  EXPECT_FALSE(quad_is_planar_convex(folded));
  folded[3].y = 1e-7f;  // 3e-8: within 2^-23 (1.2e-7) of the extent
  EXPECT_TRUE(quad_is_planar_convex(folded));
  C dart = rectangle;  // p3 pulled inside: the boundary turns the other way there
  dart[3] = glm::vec3(1, 0, 1);
  EXPECT_FALSE(quad_is_planar_convex(dart));
  const C bow_tie = {rectangle[0], rectangle[1], rectangle[3], rectangle[2]};  // p2 and p3 swapped
  EXPECT_FALSE(quad_is_planar_convex(bow_tie));
  const C flat = {glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(2, 0, 0), glm::vec3(3, 0, 0)};
  EXPECT_FALSE(quad_is_planar_convex(flat));
  // Parallelograms turned at random, corners rounded to float near the origin, as the editor
  // makes them: nearly all stay within the tolerance.
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  auto unit = [&] { glm::dvec3 v(g(rng), g(rng), g(rng)); return glm::normalize(v); };
  int planar = 0;
  for (int i = 0; i < 1000; ++i) {
    const glm::dvec3 p0 = 2.0 * unit(), e1 = unit(), e2 = glm::normalize(glm::cross(e1, unit()));
    planar += quad_is_planar_convex({glm::vec3(p0), glm::vec3(p0 + e1), glm::vec3(p0 + e2), glm::vec3(p0 + e1 + e2)});
  }
  EXPECT_GE(planar, 900);

  Scene s;
  s.materials.push_back(Material{});
  s.quads.push_back({.corners = rectangle});
  EXPECT_FALSE(scene_features(s).has_general_quads);
  s.quads.push_back({.corners = dart});
  const ShaderFeatures general = scene_features(s);
  EXPECT_TRUE(general.has_general_quads);
  EXPECT_EQ(shader_defines(general).find("GLINT_NO_GENERAL_QUADS"), std::string::npos);
  s.quads.pop_back();
  const ShaderFeatures planar_only = scene_features(s);
  EXPECT_NE(shader_defines(planar_only).find("#define GLINT_NO_GENERAL_QUADS\n"), std::string::npos);
  EXPECT_TRUE(covers(general, planar_only));
  EXPECT_FALSE(covers(planar_only, general));
}

// Which quad lights the affine sampler may take (renderer/quad_shape.h), and the feature: only
// emitting quads count.
TEST(ShaderFeatures, ParallelogramQuadLights) {
  using C = std::array<glm::vec3, 4>;
  const C rectangle = {glm::vec3(0, 0, 0), glm::vec3(0, 0, 2), glm::vec3(3, 0, 0), glm::vec3(3, 0, 2)};
  EXPECT_TRUE(quad_is_parallelogram(rectangle));
  const C skewed = {glm::vec3(0, 0, 0), glm::vec3(0.5f, 1, 2), glm::vec3(3, 0.25f, 0), glm::vec3(3.5f, 1.25f, 2)};
  EXPECT_TRUE(quad_is_parallelogram(skewed));
  C trapezoid = rectangle;
  trapezoid[3] = glm::vec3(2, 0, 2);
  EXPECT_FALSE(quad_is_parallelogram(trapezoid));
  C off = rectangle;
  off[3].y = 1e-5f;  // 2.8e-6 of the diagonal (sqrt(13)): not within 2^-21
  EXPECT_FALSE(quad_is_parallelogram(off));
  off[3].y = 1e-7f;  // within it
  EXPECT_TRUE(quad_is_parallelogram(off));
  const C flat = {glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(2, 0, 0), glm::vec3(3, 0, 0)};
  EXPECT_FALSE(quad_is_parallelogram(flat));
  // Parallelograms turned at random, corners rounded to float: nearly all pass.
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  auto unit = [&] { glm::dvec3 v(g(rng), g(rng), g(rng)); return glm::normalize(v); };
  int passed = 0;
  for (int i = 0; i < 1000; ++i) {
    const glm::dvec3 p0 = 2.0 * unit(), e1 = unit(), e2 = unit();
    passed += quad_is_parallelogram({glm::vec3(p0), glm::vec3(p0 + e1), glm::vec3(p0 + e2), glm::vec3(p0 + e1 + e2)});
  }
  EXPECT_GE(passed, 900);

  Scene s;
  s.materials.push_back(Material{});
  Material lamp;
  lamp.name = "lamp";
  lamp.emission = glm::vec3(4);
  s.materials.push_back(lamp);
  s.quads.push_back({.material = "lamp", .corners = rectangle});
  s.quads.push_back({.corners = trapezoid});  // not emitting: does not count
  const ShaderFeatures parallelograms = scene_features(s);
  EXPECT_FALSE(parallelograms.has_general_quad_lights);
  EXPECT_NE(shader_defines(parallelograms).find("#define GLINT_NO_GENERAL_QUAD_LIGHTS\n"), std::string::npos);
  s.quads.back().material = "lamp";
  const ShaderFeatures general = scene_features(s);
  EXPECT_TRUE(general.has_general_quad_lights);
  EXPECT_EQ(shader_defines(general).find("GLINT_NO_GENERAL_QUAD_LIGHTS"), std::string::npos);
  EXPECT_TRUE(covers(general, parallelograms));
  EXPECT_FALSE(covers(parallelograms, general));
}

TEST(ShaderFeatures, SamplerDefinesAndCover) {
  ShaderFeatures pcg = generic_features(), sobol = generic_features();
  pcg.sobol_sampler = false;
  sobol.pcg_sampler = false;
  EXPECT_EQ(shader_defines(pcg), "#define GLINT_NO_SOBOL_SAMPLER\n");
  EXPECT_EQ(shader_defines(sobol), "#define GLINT_NO_PCG_SAMPLER\n");
  EXPECT_TRUE(covers(generic_features(), pcg));
  EXPECT_FALSE(covers(pcg, sobol));
  EXPECT_FALSE(covers(sobol, pcg));
  ShaderFeatures scene = scene_features(Scene{});
  EXPECT_TRUE(scene.pcg_sampler && scene.sobol_sampler);  // the render options decide
}

TEST(ShaderFeatures, TraversalDefinesAndCover) {
  ShaderFeatures loop = generic_features(), bvh = generic_features();
  loop.bvh_traversal = false;
  bvh.loop_traversal = false;
  EXPECT_EQ(shader_defines(loop), "#define GLINT_NO_BVH\n");
  EXPECT_EQ(shader_defines(bvh), "#define GLINT_NO_LOOP\n");
  EXPECT_TRUE(covers(generic_features(), loop));
  EXPECT_TRUE(covers(generic_features(), bvh));
  EXPECT_FALSE(covers(loop, bvh));
  EXPECT_FALSE(covers(bvh, loop));
  // The scene alone keeps both (the renderer narrows them).
  Scene s;
  EXPECT_TRUE(scene_features(s).loop_traversal && scene_features(s).bvh_traversal);
}


// A scene that the loop alone traverses, with at most kLoopShapesMax of each shape, gets a
// program for its exact counts (renderer/loop_shapes.h); it covers only scenes of those counts,
// and a program for any count covers it.
TEST(ShaderFeatures, LoopCountsDefinesAndCover) {
  ShaderFeatures loop = generic_features();
  loop.bvh_traversal = false;
  ShaderFeatures fixed = with_loop_counts(loop, 9, 0);
  EXPECT_EQ(fixed.loop_spheres, 9);
  EXPECT_EQ(fixed.loop_quads, 0);
  EXPECT_EQ(shader_defines(fixed),
            "#define GLINT_NO_BVH\n#define GLINT_LOOP_SPHERES 9\n#define GLINT_LOOP_QUADS 0\n");
  EXPECT_TRUE(covers(generic_features(), fixed));
  EXPECT_TRUE(covers(loop, fixed));
  EXPECT_TRUE(covers(fixed, fixed));
  EXPECT_FALSE(covers(fixed, loop)) << "a program for 9 spheres cannot trace any number";
  EXPECT_FALSE(covers(fixed, with_loop_counts(loop, 10, 0)));
  EXPECT_FALSE(covers(fixed, with_loop_counts(loop, 9, 1)));
  // The limits: kLoopShapesMax of each kind unrolls, one more does not.
  EXPECT_EQ(with_loop_counts(loop, kLoopShapesMax, kLoopShapesMax).loop_quads, kLoopShapesMax);
  EXPECT_EQ(with_loop_counts(loop, kLoopShapesMax + 1, 0).loop_spheres, -1);
  EXPECT_EQ(with_loop_counts(loop, 0, kLoopShapesMax + 1).loop_quads, -1);
  EXPECT_EQ(shader_defines(with_loop_counts(loop, 0, kLoopShapesMax + 1)), "#define GLINT_NO_BVH\n");
  // Only a program that has the loop and not the BVH: the BVH's (or one with both, chosen by a
  // uniform) reads the tables.
  ShaderFeatures bvh = generic_features();
  bvh.loop_traversal = false;
  EXPECT_EQ(with_loop_counts(bvh, 9, 0).loop_spheres, -1);
  EXPECT_EQ(with_loop_counts(generic_features(), 9, 0).loop_spheres, -1);
  // And counts set before are cleared when the scene grows past the limit.
  EXPECT_EQ(with_loop_counts(fixed, 40, 0).loop_spheres, -1);
  EXPECT_EQ(with_loop_counts(fixed, 40, 0).loop_quads, -1);
}

}  // namespace
}  // namespace glint
