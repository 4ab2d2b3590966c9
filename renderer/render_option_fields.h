// The fields of RenderOptions (render_options.h), listed once: each says whether it changes the
// samples a render takes, and where it does not, why. A render part's digest (render_part.h,
// render_digest) hashes exactly the fields that change the samples, so `glint merge` refuses to
// join parts rendered with different ones.
//
// A member added to RenderOptions fails to compile below (the structured binding of
// every_option_is_listed) until the table lists it and its count is raised.
#pragma once

#include <cstddef>

#include "renderer/render_options.h"

namespace glint {

// One entry: the member and, for a field left out of the digest, why it may differ between the
// parts of one render (nullptr for a field that changes the samples, which the digest covers).
template <class M>
struct OptionField {
  const char* name;
  M RenderOptions::*member;
  const char* not_in_digest_because = nullptr;
  constexpr bool in_digest() const { return not_in_digest_because == nullptr; }
};
template <class M>
constexpr OptionField<M> changes_samples(const char* name, M RenderOptions::*member) {
  return {name, member, nullptr};
}
template <class M>
constexpr OptionField<M> same_samples(const char* name, M RenderOptions::*member, const char* because) {
  return {name, member, because};
}

// v(field) for each field of RenderOptions, in declaration order.
template <class V>
constexpr void visit_render_option_fields(V&& v) {
  v(changes_samples("light_sampling", &RenderOptions::light_sampling));
  v(changes_samples("environment_sampling", &RenderOptions::environment_sampling));
  v(changes_samples("russian_roulette", &RenderOptions::russian_roulette));
  v(changes_samples("sampler", &RenderOptions::sampler));
  v(changes_samples("clamp", &RenderOptions::clamp));
  v(same_samples("accel", &RenderOptions::accel,
                 "the loop and the BVH find the same closest hits: the same image bit for bit "
                 "(tests/gl/bvh_test.cpp)"));
  v(same_samples("restart", &RenderOptions::restart,
                 "each sample is the same and added in the same order either way: the same image "
                 "bit for bit (tests/gl/path_restart_test.cpp)"));
  v(same_samples("first_sample", &RenderOptions::first_sample,
                 "it is where a part's sample range starts, which differs between the parts of one "
                 "render; the range is in the part's header on its own and merge checks the ranges"));
  // Adaptive sampling decides which pixels take each pass's samples.
  v(changes_samples("adaptive", &RenderOptions::adaptive));
  v(changes_samples("adaptive_min_samples", &RenderOptions::adaptive_min_samples));
  v(changes_samples("adaptive_every", &RenderOptions::adaptive_every));
  v(same_samples("transparent_background", &RenderOptions::transparent_background,
                 "parts are never rendered with it: `glint render --alpha` is refused with "
                 "--samples, so every part has the opaque background (and old parts keep their "
                 "digests)"));
}

constexpr size_t render_option_field_count() {
  size_t n = 0;
  visit_render_option_fields([&](const auto&) { ++n; });
  return n;
}

// RenderOptions' members, one name each: a new member makes the binding fail to compile. The
// count beside it is that of the table.
[[maybe_unused]] inline void every_option_is_listed(const RenderOptions& o) {
  [[maybe_unused]] const auto& [a, b, c, d, e, f, g, h, i, j, k, l] = o;
  static_assert(render_option_field_count() == 12);
}

}  // namespace glint
