// Values the properties panel shows in another form than the scene stores: a quad's rotation as
// Euler angles, a material's emission as a colour (0 to 1) times a strength. Each form has many
// equivalents (the Euler angles (a, b, c) and (a + 180, 180 - b, c + 180) turn a quad alike; a
// colour and a strength can be scaled against each other), so deriving the form from the scene
// afresh each frame turns what the user typed into other numbers. The panel keeps the form it
// last showed while the scene still holds what that form produced; after another change (the
// gizmo, undo) it derives the form nearest to the one it showed.
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "renderer/scene.h"

namespace glint {

// The Euler angles shown for one quad (index), and the corners they were shown for.
struct QuadRotationView {
  int quad = -1;
  std::array<glm::vec3, 4> corners{};
  glm::vec3 rotation_deg{0};
};

// The X-Y-Z Euler angles (degrees, as QuadPlacement's) to show for quads[index]: the remembered
// ones while its corners are unchanged, else those of its orientation nearest to the remembered
// ones (the canonical ones, |Y| <= 90, for another quad), which are then remembered.
glm::vec3 shown_rotation(QuadRotationView& view, int index, const Quad& quad);
// After the panel set quads[index] from typed or dragged angles: shows exactly those from now on.
void remember_rotation(QuadRotationView& view, int index, const Quad& quad, glm::vec3 rotation_deg);

// Of the X-Y-Z Euler angles that turn a frame like `rotation` (a rotation matrix, columns the
// frame's axes), those nearest to `near_deg`, each within -360..360.
glm::vec3 euler_xyz_near(const glm::mat3& rotation, glm::vec3 near_deg);

// A material's emission as the panel shows it: a colour (each channel 0 to 1) and a strength
// (0 or more, unbounded): emission = colour * strength.
struct EmissionForm {
  glm::vec3 colour{1};
  float strength = 0;
};
struct EmissionView {
  int material = -1;
  glm::vec3 emission{0};
  EmissionForm form;
};
// The form to show for materials[index] of this emission: the remembered one while the emission
// is what it produced, else white at strength 0 for none, else the colour scaled to a brightest
// channel of 1 and that channel's value as the strength.
EmissionForm shown_emission(const EmissionView& view, int index, glm::vec3 emission);
// The emission of a form the user set (channels clamped to 0..1, a negative or non-finite
// strength to 0), remembered so that the panel shows that form (a colour chosen at strength 0
// stays chosen).
glm::vec3 set_emission(EmissionView& view, int index, EmissionForm form);

}  // namespace glint
