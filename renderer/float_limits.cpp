#include "renderer/float_limits.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "renderer/gpu_scene.h"
#include "renderer/json_fields.h"

namespace glint {
namespace {

using json_fields::child_path;
using json_fields::float_text;
using json_fields::index_path;

const std::string kRadianceReason = " (the renderer sums radiance in 32-bit floats)";
const std::string kCoordinateReason = " (beyond it the renderer's 32-bit float intersection overflows)";

struct Limits {
  std::vector<ProjectError> problems;

  void add(std::string path, std::string problem) {
    problems.emplace_back("", std::move(path), std::move(problem));
  }
  void radiance(const std::string& path, float value) {
    if (std::isfinite(value) && !(value <= kMaxRadiance))
      add(path, "must be at most " + float_text(kMaxRadiance) + " (got " + float_text(value) + ")" +
                    kRadianceReason);
  }
  void coordinate(const std::string& path, float value) {
    if (std::isfinite(value) && !(std::fabs(value) <= kMaxCoordinate))
      add(path, "must be at most " + float_text(kMaxCoordinate) + " in magnitude (got " +
                    float_text(value) + ")" + kCoordinateReason);
  }
  void coordinates(const std::string& path, glm::vec3 v) {
    for (int i = 0; i < 3; ++i) coordinate(index_path(path, i), v[i]);
  }
};

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

float max_abs(glm::vec3 v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); }

// Half the spacing of floats at `x` (x >= 0): the rounding of a float of that magnitude.
double half_ulp(float x) {
  return 0.5 * (double(std::nextafter(x, std::numeric_limits<float>::infinity())) - double(x));
}

void check_camera_near_spheres(Limits& l, const Scene& scene) {
  const Camera& cam = scene.camera;
  if (!finite(cam.position) || max_abs(cam.position) > kMaxCoordinate) return;
  const glm::dvec3 origin = render_origin(cam.position);
  const glm::dvec3 eye(glm::vec3(glm::dvec3(cam.position) - origin));  // as the GPU gets it
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& s = scene.spheres[i];
    if (!finite(s.center) || !(s.radius > 0) || max_abs(s.center) > kMaxCoordinate ||
        !(s.radius <= kMaxCoordinate))
      continue;
    // As the GPU gets it: the centre relative to the render origin, rounded to float.
    const glm::vec3 center(glm::dvec3(s.center) - origin);
    const double rounding = half_ulp(std::max(max_abs(center), s.radius));
    const double distance = std::fabs(glm::length(eye - glm::dvec3(center)) - double(s.radius));
    if (distance > rounding) continue;
    char text[256];
    std::snprintf(text, sizeof text,
                  "the camera is %.3g from the surface (radius %s), not farther than the 32-bit "
                  "float rounding of the sphere's position (%.3g): move the camera away or make "
                  "the sphere smaller",
                  distance, float_text(s.radius).c_str(), rounding);
    l.add(index_path("spheres", i), text);
  }
}

}  // namespace

std::vector<ProjectError> check_float_limits(const Scene& scene) {
  Limits l;
  l.coordinates("camera.position", scene.camera.position);
  l.coordinates("camera.target", scene.camera.target);
  // A saved view becomes the camera when recalled: the same limits.
  for (size_t i = 0; i < scene.views.size(); ++i) {
    const std::string path = child_path(index_path("views", i), "camera");
    l.coordinates(child_path(path, "position"), scene.views[i].camera.position);
    l.coordinates(child_path(path, "target"), scene.views[i].camera.target);
  }

  const Environment& env = scene.environment;
  if (env.texture.empty()) {
    // The shader's constant environment radiance is colour * intensity in float.
    for (int i = 0; i < 3; ++i) {
      const float product = env.color[i] * env.intensity;
      if (std::isfinite(env.color[i]) && std::isfinite(env.intensity) && !(product <= kMaxRadiance))
        l.add("environment.intensity",
              "times environment.color[" + std::to_string(i) + "] (" + float_text(env.color[i]) +
                  ") gives a radiance of " + float_text(product) + ", above the limit of " +
                  float_text(kMaxRadiance) + kRadianceReason);
    }
  } else {
    l.radiance("environment.intensity", env.intensity);  // times the texels
  }
  for (size_t i = 0; i < scene.materials.size(); ++i)
    for (int k = 0; k < 3; ++k)
      l.radiance(index_path(child_path(index_path("materials", i), "emission"), k),
                 scene.materials[i].emission[k]);
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const std::string path = index_path("spheres", i);
    l.coordinates(child_path(path, "center"), scene.spheres[i].center);
    l.coordinate(child_path(path, "radius"), scene.spheres[i].radius);
  }
  for (size_t i = 0; i < scene.quads.size(); ++i)
    for (size_t k = 0; k < 4; ++k)
      l.coordinates(index_path(child_path(index_path("quads", i), "corners"), k),
                    scene.quads[i].corners[k]);
  check_camera_near_spheres(l, scene);
  return l.problems;
}

}  // namespace glint
