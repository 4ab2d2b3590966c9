#include "renderer/scene_validation.h"

#include <cmath>
#include <cstdio>
#include <map>

#include "renderer/float_limits.h"
#include "renderer/json_fields.h"
#include "renderer/scene_fields.h"
#include "renderer/scene_images.h"

namespace glint {

using json_fields::child_path;
using json_fields::float_text;
using json_fields::index_path;
using json_fields::quote_name;

namespace {

class Checker {
 public:
  explicit Checker(const Scene& scene) : scene_(scene) {}
  std::vector<ProjectError> problems;

  void add(std::string path, std::string problem) {
    problems.emplace_back("", std::move(path), std::move(problem));
  }
  bool finite(const std::string& path, float v) {
    if (!std::isfinite(v)) add(path, "must be a finite number (got " + float_text(v) + ")");
    return std::isfinite(v);
  }
  // A number of a table (scene_fields.h) with its check; false when a float is not finite.
  bool number(const std::string& path, float v, const FieldCheck& k) {
    const float lo = static_cast<float>(k.lo), hi = static_cast<float>(k.hi);
    if (k.kind == FieldCheck::none) return true;
    if (!finite(path, v)) return false;
    switch (k.kind) {
      case FieldCheck::at_least:
        if (!(v >= lo)) add(path, "must be at least " + float_text(lo) + " (got " + float_text(v) + ")");
        break;
      case FieldCheck::greater_than:
        if (!(v > lo))
          add(path, "must be greater than " + float_text(lo) + " (got " + float_text(v) + ")");
        break;
      case FieldCheck::unit_interval:
        if (!(v >= 0 && v <= 1)) add(path, "must be in [0, 1] (got " + float_text(v) + ")");
        break;
      case FieldCheck::open_interval_degrees:
        if (!(v > lo && v < hi))
          add(path, "must be in (" + float_text(lo) + ", " + float_text(hi) + ") degrees (got " +
                        float_text(v) + ")");
        break;
      default: break;
    }
    return true;
  }
  void integer(const std::string& path, int64_t v, const FieldCheck& k) {
    if (k.kind != FieldCheck::integer_in) return;
    const auto min = static_cast<int64_t>(k.lo), max = static_cast<int64_t>(k.hi);
    if (v < min || v > max) add(path, json_fields::integer_range_problem(min, max, std::to_string(v)));
  }
  void not_empty(const std::string& path, const std::string& text) {
    if (text.empty()) add(path, "must not be empty");
  }
  // Reports the second and later uses of a name within one list.
  void unique(std::map<std::string, std::string>& seen, const std::string& path,
              const std::string& name, const char* what) {
    if (name.empty()) return;
    auto [it, inserted] = seen.emplace(name, path);
    if (!inserted)
      add(path, std::string("duplicate ") + what + " name " + quote_name(name) + " (first at " +
                    it->second + ")");
  }
  void material_ref(const std::string& path, const std::string& name) {
    if (find_material(scene_, name) < 0) add(path, "unknown material " + quote_name(name));
  }
  void texture_ref(const std::string& path, const std::string& name) {
    if (!name.empty() && find_texture(scene_, name) < 0)
      add(path, "unknown texture " + quote_name(name));
  }
  // The files themselves are checked by check_scene_images (scene_images.h).
  void image_path(const std::string& path, const std::string& file) {
    // The OS would see only the part before the NUL: another file than the one named.
    if (file.find('\0') != std::string::npos)
      add(path, "contains a NUL character (\\u0000), which no file name can hold");
  }

 private:
  const Scene& scene_;
};

template <int N>
bool all_finite(const glm::vec<N, float>& v) {
  for (int i = 0; i < N; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

// The checks that involve more than one field, after the fields they involve.
// `path` is the camera's JSON path: "camera", or "views[2].camera" for a saved view.
void check_camera_view(Checker& c, const std::string& path, const Camera& cam) {
  if (!all_finite(cam.position) || !all_finite(cam.target)) return;
  const glm::dvec3 view = glm::dvec3(cam.target) - glm::dvec3(cam.position);
  if (view == glm::dvec3(0)) {
    c.add(child_path(path, "target"), "must differ from " + child_path(path, "position"));
  } else if (all_finite(cam.up)) {
    const glm::dvec3 u(cam.up);
    // |sin| of the angle between up and the view direction
    if (u == glm::dvec3(0) ||
        glm::length(glm::cross(glm::normalize(view), glm::normalize(u))) <= 1e-6)
      c.add(child_path(path, "up"), "must not be zero or parallel to the view direction");
  }
}

// A quad's triangles (p0, p1, p2) and (p1, p3, p2) must each have an area: |cross| of two edges
// above 1e-12 * scale^2, where scale is the largest distance between two corners.
void check_quad_area(Checker& c, const std::string& path, const std::array<glm::vec3, 4>& p) {
  for (const glm::vec3& corner : p)
    if (!all_finite(corner)) return;
  std::array<glm::dvec3, 4> q;
  for (int i = 0; i < 4; ++i) q[i] = p[i];
  double scale2 = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) scale2 = std::max(scale2, glm::dot(q[i] - q[j], q[i] - q[j]));
  const double tolerance = 1e-12 * scale2;
  if (glm::length(glm::cross(q[1] - q[0], q[2] - q[0])) <= tolerance)
    c.add(path, "zero-area quad (triangle p0, p1, p2 is degenerate)");
  else if (glm::length(glm::cross(q[3] - q[1], q[2] - q[1])) <= tolerance)
    c.add(path, "zero-area quad (triangle p1, p3, p2 is degenerate)");
}

template <class M>
void check_value(Checker& c, const std::string& path, const M& v, const FieldCheck& k) {
  if constexpr (std::is_same_v<M, float>) {
    c.number(path, v, k);
  } else if constexpr (std::is_integral_v<M>) {
    c.integer(path, static_cast<int64_t>(v), k);
  } else if constexpr (std::is_same_v<M, glm::vec2> || std::is_same_v<M, glm::vec3>) {
    for (int i = 0; i < M::length(); ++i) check_value(c, index_path(path, i), v[i], k);
  } else if constexpr (std::is_same_v<M, std::array<glm::vec3, 4>> ||
                       std::is_same_v<M, std::array<glm::vec2, 4>>) {
    for (size_t i = 0; i < v.size(); ++i) check_value(c, index_path(path, i), v[i], k);
  }
}

// The checks of one object's fields, in table order; `names` collects a list's unique names.
template <class T>
void check_object(Checker& c, const std::string& path, const T& object,
                  std::map<std::string, std::string>* names = nullptr) {
  FieldTable<T>::visit([&](const auto& f) {
    const auto& value = object.*f.member;
    const std::string key_path = child_path(path, f.key);
    using M = typename std::decay_t<decltype(f)>::Type;
    if constexpr (std::is_same_v<M, std::string>) {
      if (f.has(kUniqueName)) {
        c.not_empty(key_path, value);
        if constexpr (requires { FieldTable<T>::noun; })
          c.unique(*names, key_path, value, FieldTable<T>::noun);
      }
      if (f.has(kAssetPath)) {
        if (!f.has(kNullable)) c.not_empty(key_path, value);
        c.image_path(key_path, value);
      }
      if (f.has(kTextureRef)) c.texture_ref(key_path, value);
      if (f.has(kMaterialRef)) c.material_ref(key_path, value);
    } else if constexpr (std::is_same_v<M, std::array<glm::vec3, 4>>) {
      check_value(c, key_path, value, f.check);
      if constexpr (std::is_same_v<T, Quad>) check_quad_area(c, key_path, value);
    } else if constexpr (kNestedObject<M>) {
      check_object(c, key_path, value);
    } else {
      check_value(c, key_path, value, f.check);
    }
  });
  if constexpr (std::is_same_v<T, Camera>) check_camera_view(c, path, object);
}

template <class T>
void check_list(Checker& c, const char* key, const std::vector<T>& list) {
  std::map<std::string, std::string> names;
  for (size_t i = 0; i < list.size(); ++i) check_object(c, index_path(key, i), list[i], &names);
}

}  // namespace

std::string too_many_problem(size_t count, size_t limit, const char* what) {
  return "too many " + std::string(what) + ": " + std::to_string(count) + " (the limit is " +
         std::to_string(limit) + ", so that their GPU array fits the 128 MiB that OpenGL 4.5 "
         "guarantees for a shader storage block)";
}

std::string too_many_views_problem(size_t count) {
  return "too many views: " + std::to_string(count) + " (the limit is " +
         std::to_string(kMaxCameraViews) + ")";
}

std::string bytes_text(double bytes) {
  const bool gib = bytes >= double(1 << 30);
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.1f %s", bytes / double(gib ? 1 << 30 : 1 << 20),
                gib ? "GiB" : "MiB");
  return buffer;
}

std::optional<ProjectError> check_film_size(int64_t width, int64_t height) {
  const bool positive = width >= 1 && height >= 1;
  const double pixels = double(width) * double(height);
  std::string memory;
  if (positive && pixels > double(kMaxFilmPixels))
    memory = "a " + std::to_string(width) + "x" + std::to_string(height) + " film would need " +
             bytes_text(pixels * kFilmBytesPerPixel) + " of GPU buffers (" +
             std::to_string(kFilmBytesPerPixel) + " bytes per pixel), the limit is " +
             bytes_text(double(kMaxFilmPixels) * kFilmBytesPerPixel) + " (" +
             std::to_string(kMaxFilmPixels) + " pixels, e.g. 8192x8192)";
  for (const auto& [key, side] : {std::pair{"film.width", width}, std::pair{"film.height", height}})
    if (side < 1 || side > kMaxFilmSide)
      return ProjectError("", key,
                          json_fields::integer_range_problem(1, kMaxFilmSide, std::to_string(side)) +
                              (memory.empty() ? "" : "; " + memory));
  if (!memory.empty()) return ProjectError("", "film", memory);
  return std::nullopt;
}

std::vector<ProjectError> validate_scene(const Scene& scene, bool check_files) {
  // The parts in file order (scene_fields.h), but the list limits right after the film, as
  // the loader reports them before any element.
  static_assert(scene_part_count() == 10, "a new part of Scene needs its checks here");
  Checker c(scene);
  check_object(c, "camera", scene.camera);
  if (const auto problem = check_film_size(scene.film.width, scene.film.height))
    c.problems.push_back(*problem);
  if (scene.spheres.size() > kMaxSpheres)
    c.add("spheres", too_many_problem(scene.spheres.size(), kMaxSpheres, "spheres"));
  if (scene.quads.size() > kMaxQuads)
    c.add("quads", too_many_problem(scene.quads.size(), kMaxQuads, "quads"));
  check_object(c, "render", scene.render);
  check_object(c, "display", scene.display);
  check_object(c, "environment", scene.environment);
  check_list(c, "textures", scene.textures);
  check_list(c, "materials", scene.materials);
  check_list(c, "spheres", scene.spheres);
  check_list(c, "quads", scene.quads);
  if (scene.views.size() > kMaxCameraViews) c.add("views", too_many_views_problem(scene.views.size()));
  check_list(c, "views", scene.views);
  for (ProjectError& problem : check_float_limits(scene)) c.problems.push_back(std::move(problem));
  if (check_files)
    for (ProjectError& problem : check_scene_images(scene)) c.problems.push_back(std::move(problem));
  return c.problems;
}

}  // namespace glint
