// The properties panel's remembered forms of rotations and emissions (see shown_values.h).
#include "editor/shown_values.h"

#include <algorithm>
#include <cmath>

#include "editor/scene_edits.h"

namespace glint {
namespace {

// `value` plus whole turns, nearest to `target`, then within -360..360 (the field's range).
float wrap_near(float value, float target) {
  float v = value + 360.0f * std::round((target - value) / 360.0f);
  if (v > 360) v -= 360;
  if (v < -360) v += 360;
  return std::abs(v) < 1e-3f ? 0.0f : v;  // never "-0.0 deg"
}

float distance2(glm::vec3 a, glm::vec3 b) { return glm::dot(a - b, a - b); }

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

glm::vec3 euler_xyz_near(const glm::mat3& r, glm::vec3 near_deg) {
  // R = Rx(a) Ry(b) Rz(c) (scene_edits.cpp's euler_xyz): its third column is
  // (sin b, -sin a cos b, cos a cos b).
  const glm::vec3 x = r[0], y = r[1], z = r[2];
  const float b = glm::degrees(std::asin(std::clamp(z.x, -1.0f, 1.0f)));
  glm::vec3 best;
  if (std::abs(z.x) < 0.99999f) {
    const float a = glm::degrees(std::atan2(-z.y, z.z)), c = glm::degrees(std::atan2(-y.x, x.x));
    // The two solutions: (a, b, c) and (a + 180, 180 - b, c + 180).
    const glm::vec3 one(wrap_near(a, near_deg.x), wrap_near(b, near_deg.y), wrap_near(c, near_deg.z));
    const glm::vec3 two(wrap_near(a + 180, near_deg.x), wrap_near(180 - b, near_deg.y), wrap_near(c + 180, near_deg.z));
    best = distance2(one, near_deg) <= distance2(two, near_deg) ? one : two;
  } else {
    // Gimbal lock (Y at +-90): only a + c (at +90) or a - c (at -90) is defined; keep c.
    const float s = glm::degrees(std::atan2(y.z, y.y));
    const float c = near_deg.z;
    const float a = z.x > 0 ? s - c : s + c;
    best = glm::vec3(wrap_near(a, near_deg.x), wrap_near(z.x > 0 ? 90.0f : -90.0f, near_deg.y), wrap_near(c, near_deg.z));
  }
  return best;
}

glm::vec3 shown_rotation(QuadRotationView& view, int index, const Quad& quad) {
  if (view.quad == index && view.corners == quad.corners) return view.rotation_deg;
  const glm::vec3 r = view.quad == index && finite(view.rotation_deg)
                          ? euler_xyz_near(quad_frame(quad), view.rotation_deg)
                          : quad_placement(quad).rotation_deg;
  view = {index, quad.corners, r};
  return r;
}

void remember_rotation(QuadRotationView& view, int index, const Quad& quad, glm::vec3 rotation_deg) {
  view = {index, quad.corners, rotation_deg};
}

EmissionForm shown_emission(const EmissionView& view, int index, glm::vec3 emission) {
  if (view.material == index && view.emission == emission) return view.form;
  const float strength = std::max({emission.x, emission.y, emission.z});
  if (!(strength > 0) || !std::isfinite(strength)) return {};
  return {emission / strength, strength};
}

glm::vec3 set_emission(EmissionView& view, int index, EmissionForm form) {
  form.colour = glm::clamp(form.colour, glm::vec3(0), glm::vec3(1));
  if (!finite(form.colour)) form.colour = glm::vec3(1);
  if (!(form.strength > 0) || !std::isfinite(form.strength)) form.strength = 0;
  const glm::vec3 emission = form.colour * form.strength;
  view = {index, emission, form};
  return emission;
}

}  // namespace glint
