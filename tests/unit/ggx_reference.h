// The sampler of GGX normals that sample_bsdf used before visible-normal sampling (Walter et
// al. 2007, "Microfacet Models for Refraction through Rough Surfaces", eq. 35-36): h with pdf
// D(h) (n.h). Kept here, in double, as an independent reference for the tests: the energy bound
// of the glossy coat and the variance comparison of the old and new samplers.
#pragma once

#include <cmath>
#include <numbers>

#include <glm/glm.hpp>

namespace glint::shader_test {

// A microfacet normal around +z with pdf D(h) cos(theta_h).
inline glm::dvec3 walter_ggx_normal(double alpha, glm::dvec2 u) {
  double phi = 2.0 * std::numbers::pi * u.x;
  double tan2 = alpha * alpha * u.y / (1.0 - u.y);
  double cos_theta = 1.0 / std::sqrt(1.0 + tan2);
  double sin_theta = std::sqrt(tan2) * cos_theta;  // not sqrt(1 - cos^2): cancels near the pole
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

}  // namespace glint::shader_test
