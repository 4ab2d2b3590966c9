// Texture-coordinate conventions of docs/DESIGN.md §6 (shaders/lib/mapping.glsl): lat-long mapping
// of directions, the environment's rotation about +Y, and bilinear repeat look-ups.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include <glm/glm.hpp>

#include "shader_test_util.h"

namespace glint::shader_test {
namespace {

using glm::dvec2;
using glm::dvec3;
constexpr double kPi = std::numbers::pi;

template <class L>
class ShaderMapping : public ::testing::Test {};
TYPED_TEST_SUITE(ShaderMapping, Precisions, PrecisionName);

// The distance between two u values on the circle (u wraps at 1).
double wrapped_distance(double a, double b) {
  double d = std::abs(a - b);
  return std::min(d, 1.0 - d);
}

TYPED_TEST(ShaderMapping, DirectionToUvFollowsTheDesignConvention) {
  using L = TypeParam;
  // u = atan2(z, x) / 2pi wrapped into [0,1), v = acos(y) / pi.
  struct Case {
    dvec3 d;
    dvec2 uv;
  };
  const double s = std::sqrt(0.5);
  for (Case k : {Case{{1, 0, 0}, {0.0, 0.5}}, Case{{0, 0, 1}, {0.25, 0.5}},
                 Case{{-1, 0, 0}, {0.5, 0.5}}, Case{{0, 0, -1}, {0.75, 0.5}},
                 Case{{s, s, 0}, {0.0, 0.25}}, Case{{0, -s, s}, {0.25, 0.75}},
                 Case{{0, 1, 0}, {0.0, 0.0}}, Case{{0, -1, 0}, {0.0, 1.0}}}) {
    typename L::vec2 uv = L::direction_to_uv(L::v3(k.d));
    EXPECT_NEAR(double(uv.x), k.uv.x, 4 * L::kEps) << k.d.x << " " << k.d.y << " " << k.d.z;
    EXPECT_NEAR(double(uv.y), k.uv.y, 4 * L::kEps) << k.d.x << " " << k.d.y << " " << k.d.z;
  }
}

// uv -> direction -> uv and direction -> uv -> direction. Near the poles u is ill-conditioned
// (a direction error e moves u by e / (2pi sin(theta))) and so is acos (dv = dy / (pi
// sin(theta))): the tolerance is 16 eps / sin(theta), 16 eps covering sin/cos/atan/acos and
// the products, each good to an ulp or two.
TYPED_TEST(ShaderMapping, DirectionAndUvAreInverse) {
  using L = TypeParam;
  Uniform u(11);
  for (int i = 0; i < 100000; ++i) {
    dvec2 uv(u(), 0.001 + 0.998 * u());
    typename L::vec3 d = L::uv_to_direction(L::v2(uv.x, uv.y));
    ASSERT_NEAR(glm::length(to_d(d)), 1.0, 8 * L::kEps);
    typename L::vec2 back = L::direction_to_uv(d);
    double tol = 16 * L::kEps / std::sin(kPi * uv.y);
    ASSERT_LE(wrapped_distance(double(back.x), uv.x), tol) << uv.x << " " << uv.y;
    ASSERT_NEAR(double(back.y), uv.y, tol) << uv.x << " " << uv.y;

    dvec3 w = u.unit_vector();
    typename L::vec3 again = L::uv_to_direction(L::direction_to_uv(L::v3(w)));
    double sin_theta = std::sqrt(std::max(1e-300, 1.0 - w.y * w.y));
    ASSERT_LE(glm::length(to_d(again) - w), 16 * L::kEps / std::max(sin_theta, 1e-3))
        << w.x << " " << w.y << " " << w.z;
  }
}

// u is in [0,1) and never exactly 1: atan2 of a zero or tiny negative z with x > 0 gives -0 or
// a tiny negative angle, and -tiny + 1 rounds to exactly 1.
TYPED_TEST(ShaderMapping, UWrapsIntoHalfOpenRange) {
  using L = TypeParam;
  using R = typename L::Real;
  std::vector<dvec3> dirs;
  for (double x : {1.0, -1.0, 0.5, -0.5, 1e-3, -1e-3}) {
    for (double z : {0.0, -0.0, 1e-45, -1e-45, 1e-38, -1e-38, 1e-30, -1e-30, 1e-9, -1e-9,
                     1e-8, -1e-8, 1e-7, -1e-7, 3e-7, -3e-7, 1e-6, -1e-6}) {
      double y = std::sqrt(std::max(0.0, 1.0 - x * x - z * z));
      dirs.push_back({x, y, z});
      dirs.push_back({x, -y, z});
    }
  }
  // Directions 1 to 1000 ulps below the seam z = 0 (x > 0), in the precision under test.
  for (int k = 1; k <= 1000; ++k) {
    R z = -std::nextafter(R(0), R(1)) * R(k);
    dirs.push_back({1.0, 0.0, double(z)});
    R z2 = -std::numeric_limits<R>::epsilon() * R(k) / R(64);
    dirs.push_back({1.0, 0.0, double(z2)});
  }
  for (dvec3 d : dirs) {
    typename L::vec3 dv(R(d.x), R(d.y), R(d.z));  // keeps -0.0 and denormals as given
    typename L::vec2 uv = L::direction_to_uv(dv);
    EXPECT_GE(uv.x, R(0)) << d.x << " " << d.y << " " << d.z;
    EXPECT_LT(uv.x, R(1)) << d.x << " " << d.y << " " << d.z;
    EXPECT_GE(uv.y, R(0));
    EXPECT_LE(uv.y, R(1));
  }
  // The negative-zero case of the brief: z = -0.0 with x < 0 is the seam's far side, u = 0.5.
  typename L::vec2 uv = L::direction_to_uv(typename L::vec3(R(-1), R(0), R(-0.0)));
  EXPECT_NEAR(double(uv.x), 0.5, 4 * L::kEps);
}

// docs/DESIGN.md §6: the environment is rotated by rotation_deg about +Y in a right-handed world
// (positive angles turn +Z towards +X, so +X goes to -Z). What the unrotated environment shows
// at direction e appears at R_y(r) e, i.e. looking along d shows the environment's direction
// R_y(-r) d, whose u is u(d) + r / 2pi. So a rotation by +90 degrees adds 0.25 to u.
TYPED_TEST(ShaderMapping, EnvironmentRotationFollowsTheRightHandRule) {
  using L = TypeParam;
  using R = typename L::Real;
  const R quarter = R(kPi / 2);
  // The environment's +X (u = 0) appears at -Z after a +90 degree turn.
  typename L::vec2 uv = L::environment_uv(L::v3(0, 0, -1), quarter);
  EXPECT_LE(wrapped_distance(double(uv.x), 0.0), 8 * L::kEps);
  EXPECT_NEAR(double(uv.y), 0.5, 8 * L::kEps);
  Uniform u(12);
  for (int i = 0; i < 10000; ++i) {
    dvec3 d = u.unit_vector();
    double sin_theta = std::sqrt(std::max(1e-300, 1.0 - d.y * d.y));
    if (sin_theta < 1e-3) continue;
    double tol = 32 * L::kEps / sin_theta;
    typename L::vec2 base = L::direction_to_uv(L::v3(d));
    typename L::vec2 plus = L::environment_uv(L::v3(d), quarter);
    typename L::vec2 minus = L::environment_uv(L::v3(d), -quarter);
    typename L::vec2 none = L::environment_uv(L::v3(d), R(0));
    double expected_plus = std::fmod(double(base.x) + 0.25, 1.0);
    double expected_minus = std::fmod(double(base.x) + 0.75, 1.0);
    ASSERT_LE(wrapped_distance(double(plus.x), expected_plus), tol) << i;
    ASSERT_LE(wrapped_distance(double(minus.x), expected_minus), tol) << i;
    ASSERT_LE(wrapped_distance(double(none.x), double(base.x)), tol) << i;
    ASSERT_NEAR(double(plus.y), double(base.y), 8 * L::kEps) << i;  // about +Y: v unchanged
  }
}

// Bilinear taps with repeat wrapping: texel centres at (i + 0.5) / w, v = 0 the first row.
TYPED_TEST(ShaderMapping, BilinearTapsWrapAtTheBorder) {
  using L = TypeParam;
  using R = typename L::Real;
  // uv = (0,0) lies halfway between the last and the first texel of a 4x4 grid.
  typename L::BilinearTaps taps = L::bilinear_taps(L::v2(0, 0), glm::ivec2(4, 4));
  EXPECT_EQ(taps.texels, glm::ivec4(3, 3, 0, 0));
  EXPECT_EQ(taps.weight, L::v2(0.5, 0.5));
  // Repeat: whole-number shifts of uv give the same taps.
  for (dvec2 uv : {dvec2(1, 1), dvec2(-1, 3), dvec2(-2, -5)}) {
    typename L::BilinearTaps t = L::bilinear_taps(L::v2(uv.x, uv.y), glm::ivec2(4, 4));
    EXPECT_EQ(t.texels, glm::ivec4(3, 3, 0, 0));
    EXPECT_EQ(t.weight, L::v2(0.5, 0.5));
  }
  typename L::BilinearTaps a = L::bilinear_taps(L::v2(-0.25, 1.25), glm::ivec2(8, 4));
  typename L::BilinearTaps b = L::bilinear_taps(L::v2(0.75, 0.25), glm::ivec2(8, 4));
  EXPECT_EQ(a.texels, b.texels);
  EXPECT_EQ(a.weight, b.weight);
  // A quarter of the way from the centre of texel 1 to texel 2 (x), first row's centre (y).
  typename L::BilinearTaps q = L::bilinear_taps(L::v2(1.75 / 4.0, 0.5 / 2.0), glm::ivec2(4, 2));
  EXPECT_EQ(q.texels, glm::ivec4(1, 0, 2, 1));
  EXPECT_EQ(q.weight, L::v2(0.25, 0.0));
  // Any uv, however far out: indices inside the grid, weights in [0, 1], x1 = x0 + 1 wrapped.
  Uniform u(13);
  for (int i = 0; i < 20000; ++i) {
    glm::ivec2 size(1 + int(u() * 300), 1 + int(u() * 300));
    double range = i % 2 ? 2.0 : 200.0;
    typename L::BilinearTaps t = L::bilinear_taps(L::v2(range * (u() - 0.5), range * (u() - 0.5)), size);
    ASSERT_TRUE(t.texels.x >= 0 && t.texels.x < size.x && t.texels.z >= 0 && t.texels.z < size.x);
    ASSERT_TRUE(t.texels.y >= 0 && t.texels.y < size.y && t.texels.w >= 0 && t.texels.w < size.y);
    ASSERT_EQ(t.texels.z, (t.texels.x + 1) % size.x);
    ASSERT_EQ(t.texels.w, (t.texels.y + 1) % size.y);
    ASSERT_TRUE(t.weight.x >= R(0) && t.weight.x <= R(1) && t.weight.y >= R(0) && t.weight.y <= R(1));
  }
}

// A texel centre reads that texel alone. For power-of-two sizes the arithmetic is exact:
// x0 = i and weight exactly 0. For other sizes (i + 0.5) / w is rounded, so the position may
// land a rounding error below the centre (x0 = i - 1, weight 1 - tiny); either way texel i
// gets all but a few eps of the weight (16 eps * w: the error of u * w - 0.5 in texels).
TYPED_TEST(ShaderMapping, TexelCentresReadOneTexel) {
  using L = TypeParam;
  using R = typename L::Real;
  for (int w : {1, 2, 4, 8, 64, 1024, 3, 5, 7, 100, 333, 1000}) {
    for (int i = 0; i < w; ++i) {
      R c = (R(i) + R(0.5)) / R(w);
      typename L::BilinearTaps t = L::bilinear_taps(typename L::vec2(c, c), glm::ivec2(w, w));
      bool pow2 = (w & (w - 1)) == 0;
      if (pow2) {
        ASSERT_EQ(t.texels.x, i) << "w = " << w;
        ASSERT_EQ(t.texels.y, i) << "w = " << w;
        ASSERT_EQ(t.weight.x, R(0)) << "w = " << w << " i = " << i;
        ASSERT_EQ(t.weight.y, R(0)) << "w = " << w << " i = " << i;
      } else {
        double on_i = (t.texels.x == i ? 1.0 - double(t.weight.x) : 0.0) +
                      (t.texels.z == i ? double(t.weight.x) : 0.0);
        if (w == 1) on_i = 1.0;  // both taps are texel 0
        ASSERT_GE(on_i, 1.0 - 16 * L::kEps * w) << "w = " << w << " i = " << i;
      }
    }
  }
}

}  // namespace
}  // namespace glint::shader_test
