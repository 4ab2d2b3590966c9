// The BVH (renderer/bvh.h, shaders/lib/bvh.glsl) against the plain loop on the GPU: the same
// image for the same seed, and scenes too large for the loop on llvmpipe render without
// discarded samples.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <random>
#include <string>

#include "gl_test_support.h"
#include "renderer/loop_budget.h"

namespace glint {
namespace {

using test::all_finite;
using test::ensure_gl_context;

Material material(std::string name, MaterialType type, glm::vec3 color, glm::vec3 emission = glm::vec3(0),
                  float roughness = 0, float opacity = 1) {
  Material m;
  m.name = std::move(name);
  m.type = type;
  m.color = color;
  m.emission = emission;
  m.roughness = roughness;
  m.opacity = opacity;
  return m;
}

// Every material type, emitters (shadow rays and MIS), a half-covered material and smooth glass
// (shadow rays pass through both), on `spheres` random spheres and `quads` random quads.
Scene random_scene(int spheres, int quads, uint32_t seed) {
  Scene s = test::empty_scene();
  s.camera.position = {0, 2, 9};
  s.camera.target = {0, 0, 0};
  s.environment.color = {0.3f, 0.35f, 0.4f};
  s.render.max_bounces = 4;
  s.materials = {material("matte", MaterialType::matte, {0.7f, 0.6f, 0.5f}),
                 material("metal", MaterialType::reflective, {0.9f, 0.8f, 0.6f}, {}, 0.2f),
                 material("glossy", MaterialType::glossy, {0.2f, 0.4f, 0.8f}, {}, 0.3f),
                 material("glass", MaterialType::transparent, {0.9f, 0.95f, 0.9f}),
                 material("cutout", MaterialType::matte, {0.8f, 0.2f, 0.2f}, {}, 0, 0.5f),
                 material("lamp", MaterialType::matte, {0.5f, 0.5f, 0.5f}, {6, 5, 4})};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1, 1);
  auto mat = [&](int i) { return s.materials[static_cast<size_t>(i) % s.materials.size()].name; };
  for (int i = 0; i < spheres; ++i) {
    Sphere sp;
    sp.name = "s" + std::to_string(i);
    sp.center = {3 * u(rng), 3 * u(rng), 3 * u(rng)};
    sp.radius = 0.15f + 0.3f * (u(rng) + 1) / 2;
    sp.material = mat(i);
    s.spheres.push_back(sp);
  }
  for (int i = 0; i < quads; ++i) {
    Quad q;
    q.name = "q" + std::to_string(i);
    q.material = mat(i + 1);
    glm::vec3 c(3 * u(rng), 3 * u(rng), 3 * u(rng)), a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    q.corners = {c, c + a, c + b, c + a + b};
    s.quads.push_back(q);
  }
  return s;
}

Image render(const Scene& s, Accel accel, int size, int passes, int spp) {
  GpuRenderer r;
  RenderOptions o;
  o.accel = accel;
  r.set_options(o);
  r.sync(s, size, size);
  EXPECT_EQ(r.uses_bvh(), accel == Accel::bvh);
  for (int i = 0; i < passes; ++i) r.trace(spp);
  return r.read_accumulation();
}

int differing_pixels(const Image& a, const Image& b) {
  int n = 0;
  for (size_t i = 0; i < a.pixels.size(); i += 4)
    if (a.pixels[i] != b.pixels[i] || a.pixels[i + 1] != b.pixels[i + 1] || a.pixels[i + 2] != b.pixels[i + 2] ||
        a.pixels[i + 3] != b.pixels[i + 3])
      ++n;
  return n;
}

double max_alpha(const Image& img) {
  double m = 0;
  for (size_t i = 3; i < img.pixels.size(); i += 4) m = std::max(m, double(img.pixels[i]));
  return m;
}

// Both find the least (t, primitive) along every ray, and the rest of the shader is shared, so
// the images are equal bit for bit when the samples are grouped into draws alike (one sample per
// pass here: the BVH draws one sample at a time, loop_budget.h, and a running mean summed in
// other groups differs by rounding) (exact comparison: any wrong hit changes a sample by far more
// than rounding). The exemption of unit.Bvh.SameHitAsTheLoop (quads seen from thousands of
// scene sizes away) does not arise in these scenes.
TEST(GlBvh, SameImageAsTheLoop) {
  ensure_gl_context();
  struct Case {
    const char* name;
    int spheres, quads;
  };
  for (Case c : {Case{"spheres", 150, 0}, Case{"quads", 0, 80}, Case{"mixed", 120, 40}}) {
    Scene s = random_scene(c.spheres, c.quads, 42);
    Image loop = render(s, Accel::loop, 32, 8, 1);
    Image bvh = render(s, Accel::bvh, 32, 8, 1);
    ASSERT_TRUE(all_finite(loop));
    EXPECT_EQ(max_alpha(loop), 0.0) << c.name;
    EXPECT_EQ(max_alpha(bvh), 0.0) << c.name;
    double mean = 0;
    for (size_t i = 0; i < loop.pixels.size(); i += 4) mean += loop.pixels[i + 1];
    std::printf("%s: mean green %.4f, %d of %d pixels differ\n", c.name, mean / (32 * 32),
                differing_pixels(loop, bvh), 32 * 32);
    EXPECT_GT(mean, 0.0) << c.name;
    EXPECT_EQ(differing_pixels(loop, bvh), 0) << c.name;
  }
}

// The generic program (both traversals compiled, u_use_bvh chooses) against the specialised one
// (GLINT_NO_LOOP): same image.
TEST(GlBvh, GenericProgramChoosesByUniform) {
  ensure_gl_context();
  Scene s = random_scene(60, 20, 7);
  auto run = [&](bool generic) {
    GpuRendererOptions ro;
    ro.force_generic_shader = generic;
    GpuRenderer r(ro);
    RenderOptions o;
    o.accel = Accel::bvh;
    r.set_options(o);
    r.sync(s, 24, 24);
    r.prepare_specialised_program();
    r.trace(4);
    EXPECT_EQ(r.last_pass_generic(), generic);
    if (!generic) {
      EXPECT_NE(r.last_pass_defines().find("GLINT_NO_LOOP"), std::string::npos);
    }
    return r.read_accumulation();
  };
  EXPECT_EQ(differing_pixels(run(true), run(false)), 0);
}

// 10^4 emitting spheres with max_bounces 0: the image is the colour of the first sphere each
// camera ray meets. The loop still fits in llvmpipe's limit here (one sample: 2 x (3 x 10002 +
// 64) = 60140 iterations), so it is the reference; the BVH must agree on every pixel.
TEST(GlBvh, TenThousandSpheresFirstHits) {
  ensure_gl_context();
  Scene s = test::empty_scene();
  s.camera.position = {0, 30, 60};
  s.camera.target = {0, 0, 0};
  s.render.max_bounces = 0;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0, 1);
  for (int i = 0; i < 8; ++i)
    s.materials.push_back(material("m" + std::to_string(i), MaterialType::matte, glm::vec3(0.5f),
                                   {u(rng), u(rng), u(rng)}));
  for (int i = 0; i < 10000; ++i) {
    Sphere sp;
    sp.name = "s" + std::to_string(i);
    sp.center = {(i % 100) - 49.5f + 0.3f * u(rng), 0.5f * u(rng), (i / 100) - 49.5f + 0.3f * u(rng)};
    sp.radius = 0.35f + 0.3f * u(rng);
    sp.material = "m" + std::to_string(i % 8);
    s.spheres.push_back(sp);
  }
  ASSERT_LE(loop_iterations_per_sample(10000, 0), kLlvmpipeLoopLimit);
  Image loop = render(s, Accel::loop, 32, 1, 2);
  Image bvh = render(s, Accel::bvh, 32, 1, 2);
  EXPECT_EQ(max_alpha(loop), 0.0);
  EXPECT_EQ(max_alpha(bvh), 0.0);
  std::printf("%d of %d pixels differ\n", differing_pixels(loop, bvh), 32 * 32);
  EXPECT_EQ(differing_pixels(loop, bvh), 0);
}

}  // namespace
}  // namespace glint
