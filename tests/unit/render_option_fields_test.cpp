// The table of RenderOptions' fields (renderer/render_option_fields.h) and the render parts'
// digest made from it (renderer/render_part.h, render_digest): changing a field that changes
// the samples changes the digest, changing any other field does not.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <type_traits>

#include "renderer/render_option_fields.h"
#include "renderer/render_part.h"

namespace glint {
namespace {

// Another value of the same field: the other bool, another enum value, one more.
template <class M>
M another(M v) {
  if constexpr (std::is_same_v<M, bool>) return !v;
  else if constexpr (std::is_enum_v<M>) return static_cast<M>(static_cast<int>(v) == 0 ? 1 : 0);
  else return v + 1;
}

TEST(RenderOptionFields, EachFieldInTheDigestChangesItAndNoOtherDoes) {
  const Scene scene;
  const RenderOptions defaults;
  const uint64_t base = render_digest(scene, defaults);
  visit_render_option_fields([&](const auto& f) {
    RenderOptions changed = defaults;
    changed.*f.member = another(defaults.*f.member);
    ASSERT_FALSE(changed == defaults) << f.name;
    if (f.in_digest()) EXPECT_NE(render_digest(scene, changed), base) << f.name << " is in the digest";
    else EXPECT_EQ(render_digest(scene, changed), base) << f.name << ": " << f.not_in_digest_because;
  });
}

TEST(RenderOptionFields, EachMemberIsListedOnceWithAReason) {
  std::set<std::string> names;
  visit_render_option_fields([&](const auto& f) {
    EXPECT_TRUE(names.insert(f.name).second) << f.name << " is listed twice";
    if (!f.in_digest()) {
      EXPECT_GT(std::string(f.not_in_digest_because).size(), 20u) << f.name;
    }
    // Changing this member changes no other: each row names its own member.
    RenderOptions changed;
    changed.*f.member = another(changed.*f.member);
    int differing = 0;
    visit_render_option_fields([&](const auto& g) {
      if (!(changed.*g.member == RenderOptions{}.*g.member)) ++differing;
    });
    EXPECT_EQ(differing, 1) << f.name;
  });
}

// Adaptive sampling decides which pixels take each pass's samples, so an adaptive render's
// parts must not merge with a uniform render's.
TEST(RenderOptionFields, AdaptiveSamplingIsInTheDigest) {
  const Scene scene;
  RenderOptions adaptive;
  adaptive.adaptive = true;
  EXPECT_NE(render_digest(scene, adaptive), render_digest(scene, RenderOptions{}));
  RenderOptions min_samples = adaptive, every = adaptive;
  min_samples.adaptive_min_samples = 32;
  every.adaptive_every = 4;
  EXPECT_NE(render_digest(scene, min_samples), render_digest(scene, adaptive));
  EXPECT_NE(render_digest(scene, every), render_digest(scene, adaptive));
}

}  // namespace
}  // namespace glint
