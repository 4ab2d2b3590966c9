// The automatic restart policy of path regeneration (renderer/path_restart.h): together where
// the environment gives light, at once where it is black; the forced ones as asked.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/path_restart.h"

namespace glint {
namespace {

Environment colour(float r, float g, float b, float intensity) {
  Environment e;
  e.color = {r, g, b};
  e.intensity = intensity;
  return e;
}

TEST(PathRestart, EnvironmentEmitsUnlessBlackOrDark) {
  EXPECT_FALSE(environment_emits(colour(0, 0, 0, 1)));
  EXPECT_FALSE(environment_emits(colour(1, 1, 1, 0)));
  EXPECT_FALSE(environment_emits(colour(1, 1, 1, std::nanf(""))));
  EXPECT_TRUE(environment_emits(colour(0, 0, 0.01f, 1)));
  EXPECT_TRUE(environment_emits(colour(0.05f, 0.06f, 0.08f, 1)));
  Environment textured = colour(0, 0, 0, 1);  // a texture's colour is not used
  textured.texture = "assets/sky.hdr";
  EXPECT_TRUE(environment_emits(textured));
  textured.intensity = 0;
  EXPECT_FALSE(environment_emits(textured));
}

TEST(PathRestart, AutomaticFollowsTheEnvironmentForcedDoesNot) {
  const Environment black = colour(0, 0, 0, 1), sky = colour(0.7f, 0.8f, 1, 1);
  EXPECT_FALSE(restart_paths_together(PathRestart::automatic, black));
  EXPECT_TRUE(restart_paths_together(PathRestart::automatic, sky));
  EXPECT_TRUE(restart_paths_together(PathRestart::together, black));
  EXPECT_FALSE(restart_paths_together(PathRestart::at_once, sky));
}

}  // namespace
}  // namespace glint
