// Camera navigation as plain maths on the scene's camera (the UI maps mouse and keys to these).
#pragma once

#include <glm/glm.hpp>

#include "renderer/scene.h"

namespace glint {

// Turntable orbit around the target: yaw about the camera's up, pitch about its right axis,
// in radians; the pitch stops short of the poles.
void orbit(Camera& camera, float yaw, float pitch);
// Moves position and target together in the view plane by a fraction of the view height at
// the target distance (delta in viewport heights; +x right, +y up).
void pan(Camera& camera, glm::vec2 delta);
// Multiplies the distance to the target by `factor` (< 1 moves closer); never reaches it.
void dolly(Camera& camera, float factor);
// WASD-style flight in the camera's frame: move.x right, move.y up, move.z forward, in world
// units; the target moves along.
void fly(Camera& camera, glm::vec3 move);
// Points the camera at a sphere of this centre and radius from its current direction, at the
// distance where it fills the view; also sets the focus distance there.
void frame(Camera& camera, glm::vec3 center, float radius);

}  // namespace glint
