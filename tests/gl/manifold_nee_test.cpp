// Manifold next-event estimation of caustics through smooth spheres (shaders/lib/
// manifold_nee.glsl): the program that adds it converges to the plain path tracer's image (the
// generic program, which has no MNEE), over the whole image and over the caustic alone (a
// missing or doubled partition of path space shows there first), with glass and mirror balls,
// sphere and quad lamps, in both back ends; merged sample ranges equal one render; and scenes
// without casters compile the program they compiled before.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "gl_test_support.h"
#include "same_picture.h"
#include "renderer/gpu_renderer.h"
#include "renderer/mnee_casters.h"
#include "renderer/part_merge.h"
#include "renderer/project_file.h"
#include "renderer/render_part.h"
#include "renderer/shader_features.h"

namespace glint {
namespace {

constexpr int kWidth = 20, kHeight = 16;
// Seeds of each estimate: their spread gives its standard error. MNEE renders 32 samples a seed,
// the path tracer 128 (its caustic is the noisier one).
constexpr int kSeeds = 12;

enum class Ball { glass, mirror, both };

// A lamp above and left of a ball on a matte floor: the ball focuses (glass) or spreads (mirror)
// the lamp's light onto the floor at its right, in view: caustic paths E D S L and E D S S L.
// The lamp is large enough that the path tracer, the reference, finds those paths often (a
// small one makes its estimate heavy-tailed, and a few seeds' spread then understates its error).
Scene caustic_scene(Ball ball, bool quad_lamp) {
  Scene s = test::empty_scene();
  s.camera.position = {0, 1.6f, 3.2f};
  s.camera.target = {0, 0.4f, 0};
  s.render.max_bounces = 8;
  s.materials.push_back({.name = "floor", .color = {0.8f, 0.8f, 0.8f}});
  s.materials.push_back({.name = "lamp", .color = {0, 0, 0}, .emission = {16, 16, 16}});
  s.materials.push_back({.name = "glass", .type = MaterialType::refractive, .color = {1, 0.9f, 0.8f}, .ior = 1.5f});
  s.materials.push_back({.name = "mirror", .type = MaterialType::reflective, .color = {0.9f, 0.8f, 0.9f}});
  s.quads.push_back({.material = "floor", .corners = {glm::vec3(-6, 0, -6), glm::vec3(-6, 0, 6),
                                                      glm::vec3(6, 0, -6), glm::vec3(6, 0, 6)}});
  if (ball == Ball::both) {
    s.spheres.push_back({.center = {0.3f, 0.4f, 0.2f}, .radius = 0.4f, .material = "glass"});
    s.spheres.push_back({.center = {-0.3f, 0.3f, -0.7f}, .radius = 0.3f, .material = "mirror"});
  } else {
    s.spheres.push_back({.center = {0, 0.5f, 0}, .radius = 0.5f, .material = ball == Ball::glass ? "glass" : "mirror"});
  }
  if (quad_lamp) {
    s.quads.push_back({.material = "lamp", .corners = {glm::vec3(-1.4f, 1.2f, -0.4f), glm::vec3(-0.6f, 1.2f, -0.4f),
                                                       glm::vec3(-1.4f, 1.2f, 0.4f), glm::vec3(-0.6f, 1.2f, 0.4f)}});
  } else {
    s.spheres.push_back({.center = {-1.0f, 1.2f, 0}, .radius = 0.25f, .material = "lamp"});
  }
  return s;
}

// A wall lit by a lamp only through a mirror ball (or a glass one, whose reflection it sees): two black shades, one on each side of the
// lamp, hide it from the wall and from the camera but not from the ball beside it, whose left side
// reflects its light onto the wall. Nearly all of the wall's light is the mirror's caustic
// (E D S L), so that MNEE counting it twice, or not at all, changes the image's mean by about
// half.
Scene mirror_caustic_on_a_wall(bool glass = false) {
  Scene s = test::empty_scene();
  s.camera.position = {0, 0.5f, 3.5f};
  s.camera.target = {0, 0.5f, -1.5f};
  s.render.max_bounces = 8;
  s.materials.push_back({.name = "wall", .color = {0.8f, 0.8f, 0.8f}});
  s.materials.push_back({.name = "lamp", .color = {0, 0, 0}, .emission = {100, 100, 100}});
  s.materials.push_back({.name = "shade", .color = {0, 0, 0}});
  s.materials.push_back({.name = "mirror", .type = MaterialType::reflective, .color = {0.9f, 0.8f, 0.9f}});
  s.quads.push_back({.material = "wall", .corners = {glm::vec3(-4, -3, -1.5f), glm::vec3(4, -3, -1.5f),
                                                     glm::vec3(-4, 4, -1.5f), glm::vec3(4, 4, -1.5f)}});
  for (float z : {-0.15f, 0.15f})
    s.quads.push_back({.material = "shade", .corners = {glm::vec3(-1.1f, 0.2f, z), glm::vec3(-0.5f, 0.2f, z),
                                                        glm::vec3(-1.1f, 0.8f, z), glm::vec3(-0.5f, 0.8f, z)}});
  // Glass of a high index reflects a third of the light at normal incidence, more at grazing.
  s.materials.push_back({.name = "glass", .type = MaterialType::refractive, .color = {1, 1, 1}, .ior = 4.0f});
  s.spheres.push_back({.center = {0, 0.5f, 0}, .radius = 0.4f, .material = glass ? "glass" : "mirror"});
  s.spheres.push_back({.center = {-0.8f, 0.5f, 0}, .radius = 0.12f, .material = "lamp"});
  return s;
}

// A sky with a sun (64 x 32 texels, the sun 3 x 3 of them at 60 times the sky, about 17
// degrees wide: large enough for the path tracer, the reference, to find it through a ball),
// written into `dir`, over a matte floor under a thin-glass pane with a mirror ball, and a
// thin-glass ball in front of it: the sun's caustics off the mirror and off the thin glass's
// outside, all through the pane (whose straight passes MNEE's segments take).
Scene sun_caustic_scene(const std::filesystem::path& dir) {
  Image sky;
  sky.width = 64;
  sky.height = 32;
  sky.pixels.assign(size_t(64) * 32 * 4, 1.0f);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      float* p = &sky.pixels[size_t(y * 64 + x) * 4];
      const bool sun = x >= 40 && x <= 42 && y >= 9 && y <= 11;
      p[0] = sun ? 60.0f : 0.3f;
      p[1] = sun ? 60.0f : 0.4f;
      p[2] = sun ? 55.0f : 0.6f;
    }
  save_image(dir / "sun.exr", sky);
  Scene s = test::empty_scene();
  s.base_dir = dir;
  s.environment.texture = "sun.exr";
  s.environment.rotation_deg = 20;
  s.camera.position = {0, 1.6f, 3.2f};
  s.camera.target = {0, 0.4f, 0};
  s.render.max_bounces = 8;
  s.materials.push_back({.name = "floor", .color = {0.8f, 0.8f, 0.8f}});
  s.materials.push_back({.name = "mirror", .type = MaterialType::reflective, .color = {0.9f, 0.8f, 0.9f}});
  s.materials.push_back({.name = "thin", .type = MaterialType::transparent, .color = {0.9f, 1, 0.8f}, .ior = 2.5f});
  s.quads.push_back({.material = "floor", .corners = {glm::vec3(-6, 0, -6), glm::vec3(-6, 0, 6),
                                                      glm::vec3(6, 0, -6), glm::vec3(6, 0, 6)}});
  s.spheres.push_back({.center = {-0.2f, 0.5f, -0.3f}, .radius = 0.5f, .material = "mirror"});
  s.spheres.push_back({.center = {0.5f, 0.35f, 0.6f}, .radius = 0.35f, .material = "thin"});
  // A thin-glass pane just above the floor: every chain to the floor passes it straight.
  s.quads.push_back({.material = "thin", .corners = {glm::vec3(-6, 0.05f, -6), glm::vec3(-6, 0.05f, 6),
                                                     glm::vec3(6, 0.05f, -6), glm::vec3(6, 0.05f, 6)}});
  return s;
}

// Mean green over seeds, of the whole image and of a region where the caustic falls (by default
// the bottom-right quarter, the floor right of the ball), with their standard errors from the
// seeds' spread.
struct Estimate {
  double mean = 0;
  double standard_error = 0;
  double caustic_mean = 0;
  double caustic_standard_error = 0;
};

using Region = bool (*)(int x, int y);
bool in_caustic_quarter(int x, int y) { return x >= kWidth / 2 && y >= kHeight / 2; }
// The wall left of the mirror ball of mirror_caustic_on_a_wall (the ball, which shows the lamp,
// and the shades are right of it).
bool on_the_wall(int x, int) { return x < kWidth / 5; }

std::pair<double, double> mean_and_error(double sum, double sum2, int n) {
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, (sum2 - n * mean * mean) / (n - 1)) / n)};
}

bool defines_mnee(const std::string& defines) { return defines.find("#define GLINT_MNEE\n") != std::string::npos; }

// Renders `seeds` seeds of `spp` samples in passes of `pass` samples; with `mnee`, the scene's
// own program (asserted to have MNEE), else the generic one (path tracing alone).
Estimate estimate(const Scene& base, bool mnee, TraceBackend backend, int spp, int pass, int seeds,
                  Region region = in_caustic_quarter) {
  GpuRendererOptions options;
  options.backend = backend;
  options.force_generic_shader = !mnee;
  options.mnee = MneeChoice::always;  // its lamps are large enough for the path tracer to converge
  GpuRenderer r(options);
  double sum = 0, sum2 = 0, caustic = 0, caustic2 = 0;
  Estimate e;
  for (int k = 0; k < seeds; ++k) {
    Scene s = base;
    s.render.seed = uint32_t(300 + k);
    r.sync(s, 1, 1);  // a fresh accumulation for each seed
    r.sync(s, kWidth, kHeight);
    if (mnee) r.prepare_specialised_program();
    for (int done = 0; done < spp; done += pass) r.trace(std::min(pass, spp - done));
    EXPECT_EQ(defines_mnee(r.last_pass_defines()), mnee);
    const Image img = r.read_accumulation();
    EXPECT_TRUE(test::all_finite(img));
    const double m = test::channel_stats(img, 1, [](int, int) { return true; }).mean;
    const double c = test::channel_stats(img, 1, region).mean;
    sum += m;
    sum2 += m * m;
    caustic += c;
    caustic2 += c * c;
  }
  std::tie(e.mean, e.standard_error) = mean_and_error(sum, sum2, seeds);
  std::tie(e.caustic_mean, e.caustic_standard_error) = mean_and_error(caustic, caustic2, seeds);
  return e;
}

// The means agree within 4 standard errors of their difference (estimated from the seeds'
// spread, so the tolerance follows the sample count).
void expect_same_image(const Estimate& with_mnee, const Estimate& path_traced, const std::string& what) {
  const double tolerance = 4 * std::hypot(with_mnee.standard_error, path_traced.standard_error);
  EXPECT_NEAR(with_mnee.mean, path_traced.mean, tolerance)
      << what << ": MNEE " << with_mnee.mean << " +- " << with_mnee.standard_error << ", path tracing "
      << path_traced.mean << " +- " << path_traced.standard_error;
  const double caustic_tolerance = 4 * std::hypot(with_mnee.caustic_standard_error, path_traced.caustic_standard_error);
  EXPECT_NEAR(with_mnee.caustic_mean, path_traced.caustic_mean, caustic_tolerance)
      << what << ", caustic region: MNEE " << with_mnee.caustic_mean << " +- " << with_mnee.caustic_standard_error
      << ", path tracing " << path_traced.caustic_mean << " +- " << path_traced.caustic_standard_error;
  EXPECT_GT(path_traced.mean, 0.01) << what;
}

// The MNEE program at 32 spp against path tracing alone at 128 (the caustic is noisier there).
void expect_path_tracers_image(const Scene& s, const char* what, TraceBackend backend = TraceBackend::fragment) {
  expect_same_image(estimate(s, true, backend, 32, 8, kSeeds), estimate(s, false, backend, 128, 32, kSeeds), what);
}

TEST(ManifoldNee, CausticScenesCompileItIn) {
  for (Ball ball : {Ball::glass, Ball::mirror, Ball::both})
    for (bool quad_lamp : {false, true}) EXPECT_TRUE(scene_needs_mnee(caustic_scene(ball, quad_lamp)));
  EXPECT_TRUE(scene_needs_mnee(mirror_caustic_on_a_wall()));
  // The renderer's automatic choice for lamps: small against the ball only.
  EXPECT_FALSE(mnee_pays_off(caustic_scene(Ball::glass, false)));
  Scene small_lamp = caustic_scene(Ball::glass, false);
  small_lamp.spheres.back().radius = 0.03f;
  EXPECT_TRUE(mnee_pays_off(small_lamp));
  EXPECT_TRUE(mnee_pays_off(load_project(std::string(GLINT_SOURCE_DIR) + "/bench/scenes/caustics.glint")));
  EXPECT_FALSE(mnee_pays_off(load_project(std::string(GLINT_SOURCE_DIR) + "/bench/scenes/glass.glint")));
  const Scene default_project = load_project(std::string(GLINT_SOURCE_DIR) + "/projects/default.glint");
  EXPECT_FALSE(mnee_pays_off(default_project));
  // Its sky has a sun, but its floor is glossy: MNEE samples neither the map nor its lamp
  // (large against the balls) unless forced.
  EXPECT_EQ(mnee_lights(default_project, kMneePeakedEnvironmentShare, false), 0);
  EXPECT_EQ(mnee_lights(default_project, 0.0, true), kMneeLamps | kMneeEnvironment);
  const Scene env_dof = load_project(std::string(GLINT_SOURCE_DIR) + "/bench/scenes/env_dof.glint");
  EXPECT_EQ(mnee_lights(env_dof, kMneePeakedEnvironmentShare, false), kMneeEnvironment);
  EXPECT_EQ(mnee_casters(caustic_scene(Ball::both, false)), (std::vector<int>{0, 1}));
}

// Scenes without a smooth ball, without a lamp MNEE samples, or without a non-delta surface
// compile the program they compiled before.
TEST(ManifoldNee, OtherScenesDoNotCompileItIn) {
  Scene matte = caustic_scene(Ball::glass, false);
  matte.materials[2] = {.name = "glass", .color = {0.5f, 0.5f, 0.5f}};
  EXPECT_FALSE(scene_needs_mnee(matte));
  Scene rough = caustic_scene(Ball::mirror, false);
  rough.materials[3].roughness = 0.2f;
  EXPECT_FALSE(scene_needs_mnee(rough));
  Scene sky = caustic_scene(Ball::glass, false);
  sky.spheres.pop_back();  // the lamp
  sky.environment.color = {1, 1, 1};
  EXPECT_FALSE(scene_needs_mnee(sky));
  EXPECT_FALSE(defines_mnee(shader_defines(scene_features(matte))));
  EXPECT_TRUE(defines_mnee(shader_defines(scene_features(caustic_scene(Ball::glass, false)))));
}

TEST(ManifoldNee, GlassBallCausticConvergesToThePathTracersImage) {
  test::ensure_gl_context();
  const Scene s = caustic_scene(Ball::glass, false);
  expect_path_tracers_image(s, "glass, sphere lamp");
}

TEST(ManifoldNee, MirrorBallCausticConvergesToThePathTracersImage) {
  test::ensure_gl_context();
  const Scene s = caustic_scene(Ball::mirror, false);
  expect_path_tracers_image(s, "mirror, sphere lamp");
}

TEST(ManifoldNee, MirrorCausticAloneConvergesToThePathTracersImage) {
  test::ensure_gl_context();
  const Scene s = mirror_caustic_on_a_wall();
  expect_same_image(estimate(s, true, TraceBackend::fragment, 512, 64, kSeeds, on_the_wall),
                    estimate(s, false, TraceBackend::fragment, 2048, 64, kSeeds, on_the_wall), "mirror caustic on a wall");
  const Scene g = mirror_caustic_on_a_wall(true);
  expect_same_image(estimate(g, true, TraceBackend::fragment, 512, 64, kSeeds, on_the_wall),
                    estimate(g, false, TraceBackend::fragment, 2048, 64, kSeeds, on_the_wall),
                    "glass's reflected caustic on a wall");
}

TEST(ManifoldNee, TwoBallsAndAQuadLampConvergeToThePathTracersImage) {
  test::ensure_gl_context();
  const Scene quad = caustic_scene(Ball::glass, true);
  expect_path_tracers_image(quad, "glass, quad lamp");
  const Scene both = caustic_scene(Ball::both, false);
  expect_path_tracers_image(both, "glass and mirror, sphere lamp");
}

// Parallel light from the environment map through a mirror and off (and straight through) thin
// glass: the MNEE program at 128 spp against path tracing at 512, and the renderer's automatic
// choice samples a peaked map (and no lamp, which this scene lacks).
TEST(ManifoldNee, SunCausticsConvergeToThePathTracersImage) {
  test::ensure_gl_context();
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("glint-gl-mnee-sun-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const Scene s = sun_caustic_scene(dir);
  EXPECT_TRUE(scene_needs_mnee(s));
  EXPECT_EQ(mnee_lights(s, 0.5, false), kMneeEnvironment);
  EXPECT_EQ(mnee_lights(s, 0.01, false), 0);
  // More samples than the lamp cases: the share of the chains through the pane (what a wrong
  // partition there doubles) is about 1.5% of the image's mean.
  expect_same_image(estimate(s, true, TraceBackend::fragment, 128, 32, kSeeds),
                    estimate(s, false, TraceBackend::fragment, 512, 64, kSeeds), "sun, mirror and thin glass");
  fs::remove_all(dir);
}

TEST(ManifoldNee, ComputeBackEndAndFewBouncesConvergeToThePathTracersImage) {
  test::ensure_gl_context();
  const Scene s = caustic_scene(Ball::glass, false);
  expect_path_tracers_image(s, "compute back end", TraceBackend::compute);
  // Two bounces: the mirror's chain from the floor (bounce 0) fits, the glass's does not.
  Scene shallow = caustic_scene(Ball::both, false);
  shallow.render.max_bounces = 2;
  expect_path_tracers_image(shallow, "max_bounces 2");
}

// Numerical stability: the caustic scene scaled by 1e-3 and 1e3, and moved by 1e4 and 1e5
// along every axis, renders with MNEE the image of the original (same seed) within the noise
// of its sample count, and when scaled far closer than that. The chains' tolerances (the
// root's residual, the Jacobian's difference step, x on the axis) are relative to the scene's
// size; an absolute one shows here.
TEST(ManifoldNee, CausticSceneScaledAndMovedRendersTheSameImage) {
  test::ensure_gl_context();
  auto render = [](const Scene& s) {
    GpuRendererOptions always;
    always.mnee = MneeChoice::always;
    GpuRenderer r(always);
    r.sync(s, 32, 24);
    r.prepare_specialised_program();
    r.trace(64);
    EXPECT_TRUE(defines_mnee(r.last_pass_defines()));
    return r.read_accumulation();
  };
  Scene base = caustic_scene(Ball::both, false);
  base.spheres.back().radius = 0.1f;  // a small lamp: most of the floor's caustics come from MNEE
  const Image original = render(base);
  Scene other_seed = base;
  other_seed.render.seed = 12345;
  const Image noise = render(other_seed);
  for (float scale : {1e-3f, 1e3f}) {
    const Image scaled = render(test::transformed(base, scale, glm::vec3(0)));
    test::expect_agreement(original, scaled, noise, scale < 1 ? "scale 1e-3" : "scale 1e3");
    // The same random numbers at another scale: only float rounding can change a path, so the
    // images are far closer than two seeds' (measured: 0.5-1.5% of that noise). Without MNEE at
    // one scale (the caustic, 1.4% of the mean, missing) they differ by 30% of it.
    const test::Agreement g = test::agreement(original, scaled, noise);
    EXPECT_LT(g.rms_difference, 0.1 * g.noise) << "scale " << scale;
  }
  for (float offset : {1e4f, 1e5f})
    test::expect_agreement(original, render(test::transformed(base, 1.0f, glm::vec3(offset, -offset, offset))), noise,
                           offset < 5e4f ? "translation 1e4" : "translation 1e5");
}

// Each sample's MNEE numbers come from its sequence index: parts rendered separately and
// merged equal the single render up to float rounding (as GlRenderParts checks for the path
// tracer).
TEST(ManifoldNee, MergedPartsEqualTheSingleRender) {
  test::ensure_gl_context();
  const Scene scene = caustic_scene(Ball::both, false);
  GpuRendererOptions always;
  always.mnee = MneeChoice::always;
  GpuRenderer r(always);
  auto render = [&](SampleRange range) {
    RenderOptions options;
    options.first_sample = static_cast<uint32_t>(range.first);
    r.set_options(options);
    r.sync(scene, 1, 1);
    r.sync(scene, kWidth, kHeight);
    r.prepare_specialised_program();
    for (int64_t done = 0, k = 1; done < range.count(); done += k, ++k)
      r.trace(static_cast<int>(std::min(k, range.count() - done)));
    EXPECT_TRUE(defines_mnee(r.last_pass_defines()));
    return r.read_accumulation();
  };
  const Image single = render({0, 12});
  std::vector<RenderPart> parts;
  for (SampleRange range : {SampleRange{0, 5}, SampleRange{5, 9}, SampleRange{9, 12}}) {
    RenderPart p;
    p.info.width = kWidth;
    p.info.height = kHeight;
    p.info.range = range;
    p.image = render(range);
    parts.push_back(std::move(p));
  }
  EXPECT_LT(test::max_relative_difference(merge_part_images(parts), single), 1e-5);
}

}  // namespace
}  // namespace glint
