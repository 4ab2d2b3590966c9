// A white Lambertian sphere under a constant environment L: every pixel is exactly L (the white
// furnace of tests/gl/renderer_test.cpp), so its reference is a constant image. Shared by the
// render-command and export tests.
#pragma once

#include "renderer/scene.h"

namespace glint::test {

inline Scene furnace_scene(int width = 32, int height = 32) {
  Scene s;
  s.camera.position = {0, 0, 5};
  s.camera.target = {0, 0, 0};
  s.film = {width, height};
  s.environment.color = {0.25f, 0.5f, 1.0f};
  s.materials.push_back({.name = "white", .color = {1, 1, 1}});
  s.spheres.push_back({.name = "ball", .center = {0, 0, 0}, .radius = 1.5f, .material = "white"});
  return s;
}

}  // namespace glint::test
