// The cache of specialised trace programs (renderer/program_variants.h) with builds the test
// finishes by hand: which program a pass gets, the LRU order and its eviction, failed builds kept
// (and never built again), and waiting. The programs are small real ones (the tonemap pass):
// the cache only hands them out.
#include <map>
#include <memory>
#include <string>

#include "renderer/gl_program.h"
#include "renderer/program_variants.h"
#include "tests/gl/gl_test_support.h"

namespace glint {
namespace {

// A build the test finishes: succeed() or fail(). wait() finishes it as a success unless told.
struct FakeBuildState {
  bool done = false;
  bool fails = false;
  bool waited = false;
  bool destroyed = false;
};

class FakeBuild final : public ProgramBuild {
 public:
  explicit FakeBuild(std::shared_ptr<FakeBuildState> state) : state_(std::move(state)) {}
  ~FakeBuild() override { state_->destroyed = true; }
  bool done() override { return state_->done; }
  void wait() override {
    state_->waited = true;
    state_->done = true;
  }
  std::unique_ptr<GlProgram> take() override {
    if (state_->fails) return nullptr;
    return std::make_unique<GlProgram>("fullscreen.vert", "tonemap.frag");
  }

 private:
  std::shared_ptr<FakeBuildState> state_;
};

struct Fixture {
  std::map<std::string, std::shared_ptr<FakeBuildState>> builds;  // by defines, the latest
  int started = 0;
  ProgramVariants variants{[this](const std::string& defines) {
    ++started;
    auto state = std::make_shared<FakeBuildState>();
    builds[defines] = state;
    return std::make_unique<FakeBuild>(state);
  }};
  std::string chosen;
  GlProgram* choose(const ShaderFeatures& f, const std::string& defines) {
    chosen.clear();
    return variants.choose(f, defines, chosen);
  }
};

// Features that need nothing but what the test names.
ShaderFeatures minimal() {
  ShaderFeatures f;
  f.has_emitters = f.has_textures = f.env_textured = f.thin_lens = f.has_coverage = false;
  f.has_spheres = f.has_quads = f.has_general_quads = f.has_general_quad_lights = false;
  return f;
}

TEST(ProgramVariants, AProgramIsHandedOutOnlyOnceBuilt) {
  test::ensure_gl_context();
  Fixture t;
  const ShaderFeatures f = minimal();
  EXPECT_EQ(t.choose(f, "A"), nullptr) << "nothing cached: the generic program";
  t.variants.start_if_missing(f, "A");
  EXPECT_EQ(t.variants.state("A"), ProgramVariants::State::building);
  EXPECT_EQ(t.choose(f, "A"), nullptr) << "still building: never waits";
  t.builds["A"]->done = true;
  GlProgram* a = t.choose(f, "A");
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(t.chosen, "A");
  EXPECT_EQ(t.variants.state("A"), ProgramVariants::State::ready);
  EXPECT_TRUE(t.builds["A"]->destroyed) << "the build is dropped once its program is taken";
  t.variants.start_if_missing(f, "A");
  EXPECT_EQ(t.started, 1) << "cached: not built again";
  EXPECT_EQ(t.choose(f, "A"), a);
}

// A failed build stays in the cache, so that the scene does not start it again at every pass;
// the generic program renders.
TEST(ProgramVariants, AFailedBuildIsKeptAndNeverRetried) {
  test::ensure_gl_context();
  Fixture t;
  const ShaderFeatures f = minimal();
  t.variants.start_if_missing(f, "A");
  t.builds["A"]->fails = true;
  t.builds["A"]->done = true;
  EXPECT_EQ(t.choose(f, "A"), nullptr);
  EXPECT_EQ(t.variants.state("A"), ProgramVariants::State::failed);
  for (int i = 0; i < 3; ++i) t.variants.start_if_missing(f, "A");
  EXPECT_EQ(t.started, 1);
  EXPECT_EQ(t.choose(f, "A"), nullptr);
}

// Without the exact variant ready, a ready one whose features cover the scene's is used (a
// feature removed by an edit), the first in LRU order; one that lacks a feature never is.
TEST(ProgramVariants, AReadyVariantThatCoversTheFeaturesStandsIn) {
  test::ensure_gl_context();
  Fixture t;
  ShaderFeatures with_spheres = minimal();
  with_spheres.has_spheres = true;
  const ShaderFeatures without = minimal();
  t.variants.start_if_missing(with_spheres, "spheres");
  t.builds["spheres"]->done = true;
  t.variants.start_if_missing(without, "none");
  GlProgram* spheres = t.choose(without, "none");
  EXPECT_EQ(spheres, t.choose(with_spheres, "spheres"));
  EXPECT_EQ(t.choose(without, "none"), spheres);
  EXPECT_EQ(t.chosen, "spheres");
  t.builds["none"]->done = true;
  GlProgram* none = t.choose(without, "none");
  EXPECT_NE(none, spheres);
  EXPECT_EQ(t.chosen, "none");
  EXPECT_EQ(t.choose(with_spheres, "spheres"), spheres) << "the exact one";
  ShaderFeatures with_quads = minimal();
  with_quads.has_quads = true;
  EXPECT_EQ(t.choose(with_quads, "quads"), nullptr) << "none covers quads";
}

// At most kCapacity variants: starting another evicts the least recently used (a build under
// way like a ready one); a choice makes a variant the most recently used; a new one starts
// as the least recently used.
TEST(ProgramVariants, TheLeastRecentlyUsedIsEvicted) {
  test::ensure_gl_context();
  Fixture t;
  const ShaderFeatures f = minimal();
  ASSERT_EQ(ProgramVariants::kCapacity, 4u);
  for (const char* key : {"A", "B", "C", "D"}) {
    t.variants.start_if_missing(f, key);
    t.builds[key]->done = true;
  }
  EXPECT_EQ(t.variants.keys(), (std::vector<std::string>{"A", "B", "C", "D"}));
  t.choose(f, "C");
  t.choose(f, "A");
  EXPECT_EQ(t.variants.keys(), (std::vector<std::string>{"A", "C", "B", "D"}));
  t.variants.start_if_missing(f, "E");  // evicts D
  EXPECT_EQ(t.variants.keys(), (std::vector<std::string>{"A", "C", "B", "E"}));
  EXPECT_EQ(t.variants.state("D"), ProgramVariants::State::absent);
  t.variants.start_if_missing(f, "F");  // evicts E, still building: its build is dropped
  EXPECT_TRUE(t.builds["E"]->destroyed);
  EXPECT_EQ(t.variants.keys(), (std::vector<std::string>{"A", "C", "B", "F"}));
  t.variants.start_if_missing(f, "D");  // built again
  EXPECT_EQ(t.started, 7);
}

TEST(ProgramVariants, WaitFinishesTheBuildOfOneVariant) {
  test::ensure_gl_context();
  Fixture t;
  const ShaderFeatures f = minimal();
  t.variants.start_if_missing(f, "A");
  t.variants.start_if_missing(f, "B");
  t.variants.wait("A");
  EXPECT_TRUE(t.builds["A"]->waited);
  EXPECT_FALSE(t.builds["B"]->waited);
  EXPECT_EQ(t.variants.state("A"), ProgramVariants::State::ready);
  EXPECT_EQ(t.variants.state("B"), ProgramVariants::State::building);
  t.builds["B"]->fails = true;
  t.variants.wait("B");
  EXPECT_EQ(t.variants.state("B"), ProgramVariants::State::failed);
  t.variants.wait("A");  // ready: nothing to wait for
  t.variants.wait("absent");
  EXPECT_NE(t.choose(f, "A"), nullptr);
}

}  // namespace
}  // namespace glint
