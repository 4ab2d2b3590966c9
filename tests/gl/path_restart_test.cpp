// Path regeneration's two restart policies (renderer/path_restart.h) trace the same samples and
// add them in the same order, so they give the same image bit for bit, with either entry point,
// the generic and the specialised programs, and either sampler.
#include <cstring>
#include <filesystem>

#include <epoxy/gl.h>

#include "renderer/path_restart.h"
#include "renderer/project_file.h"
#include "tests/gl/gl_test_support.h"

namespace glint {
namespace {

// 21x13: neither side a multiple of llvmpipe's SIMD groups or of the 8x8 work group.
constexpr int kWidth = 21, kHeight = 13;

Image render(GpuRenderer& r, const Scene& scene, PathRestart restart, SamplerKind sampler) {
  RenderOptions options;
  options.restart = restart;
  options.sampler = sampler;
  r.set_options(options);
  r.sync(scene, kWidth, kHeight);
  // Passes of several sizes, so that a pass ends with lanes waiting and without.
  for (int k : {1, 3, 5}) r.trace(k);
  return r.read_accumulation();
}

bool same_bits(const Image& a, const Image& b) {
  return a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

TEST(GlPathRestart, SameImageEitherWayForEveryExampleProject) {
  test::ensure_gl_context();
  // On llvmpipe (CI) the driver has group votes, so the waiting path is the one compiled.
  if (on_llvmpipe()) {
    EXPECT_TRUE(epoxy_has_gl_extension("GL_ARB_shader_group_vote"));
  }
  int count = 0;
  for (TraceBackend backend : {TraceBackend::fragment, TraceBackend::compute}) {
    GpuRendererOptions options;
    options.backend = backend;
    options.force_generic_shader = true;
    GpuRenderer r(options);
    for (const auto& entry : std::filesystem::directory_iterator(GLINT_SOURCE_DIR "/projects")) {
      if (entry.path().extension() != ".glint") continue;
      SCOPED_TRACE(entry.path().filename().string() + (backend == TraceBackend::compute ? " compute" : " fragment"));
      const Scene scene = load_project(entry.path());
      const Image at_once = render(r, scene, PathRestart::at_once, SamplerKind::sobol);
      const Image together = render(r, scene, PathRestart::together, SamplerKind::sobol);
      EXPECT_TRUE(test::all_finite(at_once));
      EXPECT_TRUE(same_bits(at_once, together));
      ++count;
    }
  }
  EXPECT_GE(count, 12);
}

TEST(GlPathRestart, SameImageWithSpecialisedProgramsAndPcg) {
  test::ensure_gl_context();
  const Scene scene = load_project(GLINT_SOURCE_DIR "/projects/default.glint");
  for (SamplerKind sampler : {SamplerKind::pcg, SamplerKind::sobol}) {
    GpuRenderer r;
    Image images[2];
    const PathRestart policies[2] = {PathRestart::at_once, PathRestart::together};
    for (int i = 0; i < 2; ++i) {
      RenderOptions options;
      options.restart = policies[i];
      options.sampler = sampler;
      r.set_options(options);
      r.sync(scene, kWidth, kHeight);
      r.prepare_specialised_program();
      for (int k : {2, 7}) r.trace(k);
      EXPECT_FALSE(r.last_pass_generic());
      images[i] = r.read_accumulation();
    }
    EXPECT_TRUE(same_bits(images[0], images[1])) << (sampler == SamplerKind::pcg ? "pcg" : "sobol");
  }
}

}  // namespace
}  // namespace glint
