#include "renderer/project_file.h"


#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>

#include "renderer/atomic_file.h"
#include "renderer/float_limits.h"
#include "renderer/image.h"
#include "renderer/json_fields.h"
#include "renderer/scene_images.h"

namespace glint {

namespace fs = std::filesystem;
using json_fields::Json;
using json_fields::ObjectReader;
using json_fields::child_path;
using json_fields::float_text;
using json_fields::index_path;

namespace {

// The parts of a message are clipped (their middle replaced by "..."), so that a message stays
// within about 600 characters whatever the file holds: a file name, path or problem that
// quotes a 50 MB key or string would otherwise repeat it in full.
constexpr size_t kMaxMessageFile = 160;
constexpr size_t kMaxMessagePath = 120;
constexpr size_t kMaxMessageProblem = 300;

std::string error_message(const std::string& file, const std::string& path,
                          const std::string& problem) {
  std::string message;
  if (!file.empty()) message += json_fields::clip(file, kMaxMessageFile) + ": ";
  if (!path.empty()) message += json_fields::clip(path, kMaxMessagePath) + ": ";
  return message + json_fields::clip(problem, kMaxMessageProblem);
}

// ---- Parsing: structure and types. Values are checked afterwards by validate_scene. ----

constexpr int kMaxBounces = 1024;

// A name in quotes for a message; invalid UTF-8 (possible in scenes built through the API)
// is shown replaced rather than thrown by nlohmann's dump.
// Long names are clipped (json_fields::clip).
std::string quote_name(const std::string& text) {
  return Json(json_fields::clip(text, json_fields::kMaxQuotedString))
      .dump(-1, ' ', false, Json::error_handler_t::replace);
}

// The array sizes of load_project's limits (project_file.h).
std::string count_problem(size_t count, size_t limit, const char* what) {
  return "too many " + std::string(what) + ": " + std::to_string(count) + " (the limit is " +
         std::to_string(limit) + ", so that their GPU array fits the 128 MiB that OpenGL 4.5 "
         "guarantees for a shader storage block)";
}

Camera parse_camera(const Json& j, const std::string& file) {
  ObjectReader r(j, "camera", file,
                 {"position", "target", "up", "vfov_deg", "aperture_radius", "focus_distance"});
  Camera c;
  r.read("position", c.position);
  r.read("target", c.target);
  r.read("up", c.up);
  r.read("vfov_deg", c.vfov_deg);
  r.read("aperture_radius", c.aperture_radius);
  r.read("focus_distance", c.focus_distance);
  return c;
}

Texture parse_texture(const Json& j, const std::string& path, const std::string& file) {
  ObjectReader r(j, path, file, {"name", "path"});
  r.require("name");
  r.require("path");
  Texture t;
  r.read("name", t.name);
  r.read("path", t.path);
  return t;
}

Material parse_material(const Json& j, const std::string& path, const std::string& file) {
  ObjectReader r(j, path, file,
                 {"name", "type", "color", "color_texture", "emission", "emission_texture",
                  "roughness", "roughness_texture", "ior", "opacity"});
  r.require("name");
  Material m;
  r.read("name", m.name);
  if (const Json* type = r.find("type")) {
    const std::string text = json_fields::read_string(*type, file, r.path("type"));
    const auto parsed = material_type_from_string(text);
    if (!parsed)
      json_fields::fail(file, r.path("type"),
                        "unknown material type " + quote_name(text) +
                            " (expected matte, reflective, glossy or transparent)");
    m.type = *parsed;
  }
  r.read("color", m.color);
  r.read_optional_string("color_texture", m.color_texture);
  r.read("emission", m.emission);
  r.read_optional_string("emission_texture", m.emission_texture);
  r.read("roughness", m.roughness);
  r.read_optional_string("roughness_texture", m.roughness_texture);
  r.read("ior", m.ior);
  r.read("opacity", m.opacity);
  return m;
}

Sphere parse_sphere(const Json& j, const std::string& path, const std::string& file) {
  ObjectReader r(j, path, file, {"name", "center", "radius", "material"});
  r.require("center");
  r.require("radius");
  r.require("material");
  Sphere s;
  r.read("name", s.name);
  r.read("center", s.center);
  r.read("radius", s.radius);
  r.read("material", s.material);
  return s;
}

Quad parse_quad(const Json& j, const std::string& path, const std::string& file) {
  ObjectReader r(j, path, file, {"name", "material", "corners", "uvs"});
  r.require("material");
  r.require("corners");
  Quad q;
  r.read("name", q.name);
  r.read("material", q.material);
  auto read_rows = [&](const char* key, auto& out, auto read_row) {
    const Json* rows = r.find(key);
    if (!rows) return;
    if (!rows->is_array() || rows->size() != out.size())
      json_fields::fail(file, r.path(key), "expected an array of 4 points, got " +
                                               json_fields::describe(*rows));
    for (size_t i = 0; i < out.size(); ++i)
      out[i] = read_row((*rows)[i], file, index_path(r.path(key), i));
  };
  read_rows("corners", q.corners, json_fields::read_vec3);
  read_rows("uvs", q.uvs, json_fields::read_vec2);
  return q;
}

// Reads the array under `key` of the root object, one element at a time; an array longer
// than `limit` is refused before any element is read.
template <class T, class Parse>
void parse_list(const ObjectReader& root, const char* key, std::vector<T>& out, Parse parse,
                const std::string& file, size_t limit = SIZE_MAX) {
  const Json* items = root.array(key);
  if (items && items->size() > limit)
    json_fields::fail(file, key, count_problem(items->size(), limit, key));
  if (items)
    for (size_t i = 0; i < items->size(); ++i)
      out.push_back(parse((*items)[i], index_path(key, i), file));
}

// ---- Validation: values and references of a complete scene. ----

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
  template <int N>
  bool finite(const std::string& path, glm::vec<N, float> v) {
    bool ok = true;
    for (int i = 0; i < N; ++i) ok = finite(index_path(path, i), v[i]) && ok;
    return ok;
  }
  void at_least(const std::string& path, float v, float min) {
    if (finite(path, v) && !(v >= min))
      add(path, "must be at least " + float_text(min) + " (got " + float_text(v) + ")");
  }
  void greater_than(const std::string& path, float v, float min) {
    if (finite(path, v) && !(v > min))
      add(path, "must be greater than " + float_text(min) + " (got " + float_text(v) + ")");
  }
  void in_unit_interval(const std::string& path, float v) {
    if (finite(path, v) && !(v >= 0 && v <= 1))
      add(path, "must be in [0, 1] (got " + float_text(v) + ")");
  }
  void non_negative(const std::string& path, glm::vec3 v) {
    for (int i = 0; i < 3; ++i) at_least(index_path(path, i), v[i], 0);
  }
  void integer_in(const std::string& path, int64_t v, int64_t min, int64_t max) {
    if (v < min || v > max)
      add(path, json_fields::integer_range_problem(min, max, std::to_string(v)));
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

void check_camera(Checker& c, const Camera& cam) {
  const bool position = c.finite("camera.position", cam.position);
  const bool points = c.finite("camera.target", cam.target) && position;
  const bool up = c.finite("camera.up", cam.up);
  if (c.finite("camera.vfov_deg", cam.vfov_deg) && !(cam.vfov_deg > 0 && cam.vfov_deg < 180))
    c.add("camera.vfov_deg", "must be in (0, 180) degrees (got " + float_text(cam.vfov_deg) + ")");
  c.at_least("camera.aperture_radius", cam.aperture_radius, 0);
  c.greater_than("camera.focus_distance", cam.focus_distance, 0);
  if (!points) return;
  const glm::dvec3 view = glm::dvec3(cam.target) - glm::dvec3(cam.position);
  if (view == glm::dvec3(0)) {
    c.add("camera.target", "must differ from camera.position");
  } else if (up) {
    const glm::dvec3 u(cam.up);
    // |sin| of the angle between up and the view direction
    if (u == glm::dvec3(0) ||
        glm::length(glm::cross(glm::normalize(view), glm::normalize(u))) <= 1e-6)
      c.add("camera.up", "must not be zero or parallel to the view direction");
  }
}

// A quad's triangles (p0, p1, p2) and (p1, p3, p2) must each have an area: |cross| of two edges
// above 1e-12 * scale^2, where scale is the largest distance between two corners.
void check_quad_area(Checker& c, const std::string& path, const std::array<glm::vec3, 4>& p) {
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

// A relative asset path rewritten for a new folder; both folders are absolute.
std::string rebase_path(const std::string& path, const fs::path& from, const fs::path& to) {
  if (path.empty() || fs::path(path).is_absolute()) return path;
  std::error_code ec;
  const fs::path target = (from / path).lexically_normal();
  const fs::path relative = fs::relative(target, to, ec);
  return (ec || relative.empty() ? target : relative).generic_string();
}

fs::path folder_identity(const fs::path& folder) {
  const fs::path absolute = fs::absolute(folder.empty() ? fs::current_path() : folder);
  std::error_code ec;
  fs::path canonical = fs::weakly_canonical(absolute, ec);
  if (ec) canonical = absolute.lexically_normal();
  return canonical.has_filename() ? canonical : canonical.parent_path();
}

}  // namespace

std::string bytes_text(double bytes) {
  const bool gib = bytes >= double(1 << 30);
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.1f %s", bytes / double(gib ? 1 << 30 : 1 << 20),
                gib ? "GiB" : "MiB");
  return buffer;
}

ProjectError::ProjectError(std::string file_, std::string json_path_, std::string problem_)
    : std::runtime_error(error_message(file_, json_path_, problem_)),
      file(std::move(file_)),
      json_path(json_fields::clip(json_path_, kMaxMessagePath)),
      problem(json_fields::clip(problem_, kMaxMessageProblem)) {}

Scene scene_from_json(const nlohmann::ordered_json& doc, const std::string& file,
                      const fs::path& base_dir, bool check_files) {
  using json_fields::fail;
  if (!doc.is_object()) fail(file, "", "expected a JSON object, got " + json_fields::describe(doc));
  // Format and version first: another kind of JSON file gets a clear message, not "unknown key".
  const auto format = doc.find("format");
  if (format == doc.end())
    fail(file, "format", "missing (a Glint project has \"format\": \"glint-project\")");
  if (*format != "glint-project")
    fail(file, "format", "expected \"glint-project\", got " + json_fields::describe(*format));
  const auto version = doc.find("version");
  if (version == doc.end()) fail(file, "version", "missing required key");
  if (*version != 1)
    fail(file, "version",
         "unsupported version " + version->dump() + " (this program reads version 1)");

  ObjectReader root(doc, "", file,
                    {"format", "version", "camera", "film", "render", "display", "environment",
                     "textures", "materials", "spheres", "quads"});
  Scene s;
  s.base_dir = base_dir;
  if (const Json* j = root.find("camera")) s.camera = parse_camera(*j, file);
  if (const Json* j = root.find("film")) {
    ObjectReader r(*j, "film", file, {"width", "height"});
    // Any integer first (saturated to int64), then the limits with a memory estimate.
    auto side = [&](const char* key, int current) -> int64_t {
      const Json* v = r.find(key);
      if (!v) return current;
      if (!v->is_number_integer()) fail(file, r.path(key), "expected an integer, got " + json_fields::describe(*v));
      if (v->is_number_unsigned() && v->get<uint64_t>() > uint64_t(INT64_MAX)) return INT64_MAX;
      return v->get<int64_t>();
    };
    const int64_t width = side("width", s.film.width), height = side("height", s.film.height);
    if (const auto problem = check_film_size(width, height))
      fail(file, problem->json_path, problem->problem);
    s.film = {static_cast<int>(width), static_cast<int>(height)};
  }
  if (const Json* j = root.find("render")) {
    ObjectReader r(*j, "render", file, {"max_bounces", "seed"});
    r.read_integer("max_bounces", 0, kMaxBounces, s.render.max_bounces);
    r.read_integer("seed", 0, UINT32_MAX, s.render.seed);
  }
  if (const Json* j = root.find("display")) {
    ObjectReader r(*j, "display", file, {"exposure", "tonemap"});
    r.read("exposure", s.display.exposure);
    std::string tonemap = to_string(s.display.tonemap);
    r.read("tonemap", tonemap);
    const auto parsed = tonemap_from_string(tonemap);
    if (!parsed)
      fail(file, "display.tonemap",
           "unknown tonemap " + quote_name(tonemap) + " (expected filmic or linear)");
    s.display.tonemap = *parsed;
  }
  if (const Json* j = root.find("environment")) {
    ObjectReader r(*j, "environment", file, {"color", "texture", "intensity", "rotation_deg"});
    r.read("color", s.environment.color);
    r.read_optional_string("texture", s.environment.texture);
    r.read("intensity", s.environment.intensity);
    r.read("rotation_deg", s.environment.rotation_deg);
  }
  parse_list(root, "textures", s.textures, parse_texture, file);
  parse_list(root, "materials", s.materials, parse_material, file);
  parse_list(root, "spheres", s.spheres, parse_sphere, file, kMaxSpheres);
  parse_list(root, "quads", s.quads, parse_quad, file, kMaxQuads);

  const auto problems = validate_scene(s, check_files);
  if (!problems.empty()) fail(file, problems.front().json_path, problems.front().problem);
  return s;
}

Scene scene_from_json(const nlohmann::json& doc, const std::string& file_label,
                      const fs::path& base_dir, bool check_files) {
  return scene_from_json(nlohmann::ordered_json(doc), file_label, base_dir, check_files);
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
  Checker c(scene);
  check_camera(c, scene.camera);
  if (const auto problem = check_film_size(scene.film.width, scene.film.height))
    c.problems.push_back(*problem);
  if (scene.spheres.size() > kMaxSpheres)
    c.add("spheres", count_problem(scene.spheres.size(), kMaxSpheres, "spheres"));
  if (scene.quads.size() > kMaxQuads)
    c.add("quads", count_problem(scene.quads.size(), kMaxQuads, "quads"));
  c.integer_in("render.max_bounces", scene.render.max_bounces, 0, kMaxBounces);
  c.finite("display.exposure", scene.display.exposure);

  const Environment& env = scene.environment;
  c.non_negative("environment.color", env.color);
  c.image_path("environment.texture", env.texture);
  c.at_least("environment.intensity", env.intensity, 0);
  c.finite("environment.rotation_deg", env.rotation_deg);

  std::map<std::string, std::string> texture_names, material_names;
  for (size_t i = 0; i < scene.textures.size(); ++i) {
    const Texture& t = scene.textures[i];
    const std::string path = index_path("textures", i);
    c.not_empty(child_path(path, "name"), t.name);
    c.unique(texture_names, child_path(path, "name"), t.name, "texture");
    c.not_empty(child_path(path, "path"), t.path);
    c.image_path(child_path(path, "path"), t.path);
  }
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    const std::string path = index_path("materials", i);
    auto field = [&](const char* key) { return child_path(path, key); };
    c.not_empty(field("name"), m.name);
    c.unique(material_names, field("name"), m.name, "material");
    c.non_negative(field("color"), m.color);
    c.texture_ref(field("color_texture"), m.color_texture);
    c.non_negative(field("emission"), m.emission);
    c.texture_ref(field("emission_texture"), m.emission_texture);
    c.in_unit_interval(field("roughness"), m.roughness);
    c.texture_ref(field("roughness_texture"), m.roughness_texture);
    c.at_least(field("ior"), m.ior, 1);
    c.in_unit_interval(field("opacity"), m.opacity);
  }
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& s = scene.spheres[i];
    const std::string path = index_path("spheres", i);
    c.finite(child_path(path, "center"), s.center);
    c.greater_than(child_path(path, "radius"), s.radius, 0);
    c.material_ref(child_path(path, "material"), s.material);
  }
  for (size_t i = 0; i < scene.quads.size(); ++i) {
    const Quad& q = scene.quads[i];
    const std::string path = index_path("quads", i);
    c.material_ref(child_path(path, "material"), q.material);
    const std::string corners = child_path(path, "corners");
    bool corners_finite = true;
    for (size_t k = 0; k < 4; ++k)
      corners_finite = c.finite(index_path(corners, k), q.corners[k]) && corners_finite;
    if (corners_finite) check_quad_area(c, corners, q.corners);
    for (size_t k = 0; k < 4; ++k) c.finite(index_path(child_path(path, "uvs"), k), q.uvs[k]);
  }
  for (ProjectError& problem : check_float_limits(scene)) c.problems.push_back(std::move(problem));
  if (check_files)
    for (ProjectError& problem : check_scene_images(scene)) c.problems.push_back(std::move(problem));
  return c.problems;
}

nlohmann::ordered_json scene_to_json(const Scene& s) {
  using json_fields::float_to_json;
  using json_fields::vec_to_json;
  auto name_or_null = [](const std::string& name) {
    return name.empty() ? Json(nullptr) : Json(name);
  };
  Json j;
  j["format"] = "glint-project";
  j["version"] = 1;
  Json& cam = j["camera"];
  cam["position"] = vec_to_json(s.camera.position);
  cam["target"] = vec_to_json(s.camera.target);
  cam["up"] = vec_to_json(s.camera.up);
  cam["vfov_deg"] = float_to_json(s.camera.vfov_deg);
  cam["aperture_radius"] = float_to_json(s.camera.aperture_radius);
  cam["focus_distance"] = float_to_json(s.camera.focus_distance);
  j["film"]["width"] = s.film.width;
  j["film"]["height"] = s.film.height;
  j["render"]["max_bounces"] = s.render.max_bounces;
  j["render"]["seed"] = s.render.seed;
  j["display"]["exposure"] = float_to_json(s.display.exposure);
  j["display"]["tonemap"] = to_string(s.display.tonemap);
  Json& env = j["environment"];
  env["color"] = vec_to_json(s.environment.color);
  env["texture"] = name_or_null(s.environment.texture);
  env["intensity"] = float_to_json(s.environment.intensity);
  env["rotation_deg"] = float_to_json(s.environment.rotation_deg);

  Json& textures = j["textures"] = Json::array();
  for (const Texture& t : s.textures) {
    Json& e = textures.emplace_back();
    e["name"] = t.name;
    e["path"] = t.path;
  }
  Json& materials = j["materials"] = Json::array();
  for (const Material& m : s.materials) {
    Json& e = materials.emplace_back();
    e["name"] = m.name;
    e["type"] = to_string(m.type);
    e["color"] = vec_to_json(m.color);
    e["color_texture"] = name_or_null(m.color_texture);
    e["emission"] = vec_to_json(m.emission);
    e["emission_texture"] = name_or_null(m.emission_texture);
    e["roughness"] = float_to_json(m.roughness);
    e["roughness_texture"] = name_or_null(m.roughness_texture);
    e["ior"] = float_to_json(m.ior);
    e["opacity"] = float_to_json(m.opacity);
  }
  Json& spheres = j["spheres"] = Json::array();
  for (const Sphere& sp : s.spheres) {
    Json& e = spheres.emplace_back();
    e["name"] = sp.name;
    e["center"] = vec_to_json(sp.center);
    e["radius"] = float_to_json(sp.radius);
    e["material"] = sp.material;
  }
  Json& quads = j["quads"] = Json::array();
  for (const Quad& q : s.quads) {
    Json& e = quads.emplace_back();
    e["name"] = q.name;
    e["material"] = q.material;
    Json& corners = e["corners"] = Json::array();
    for (const glm::vec3& p : q.corners) corners.push_back(vec_to_json(p));
    Json& uvs = e["uvs"] = Json::array();
    for (const glm::vec2& uv : q.uvs) uvs.push_back(vec_to_json(uv));
  }
  return j;
}

std::string project_file_text(const Scene& scene) {
  return json_fields::pretty_print(scene_to_json(scene));
}

Scene rebase_asset_paths(const Scene& scene, const fs::path& new_base_dir) {
  Scene out = scene;
  out.base_dir = new_base_dir;
  // The same path is the same folder: no file system calls (the fuzz target saves every input).
  if (scene.base_dir == new_base_dir) return out;
  const fs::path from = folder_identity(scene.base_dir), to = folder_identity(new_base_dir);
  if (from == to) return out;  // same folder: keep the paths exactly as they are
  for (Texture& t : out.textures) t.path = rebase_path(t.path, from, to);
  out.environment.texture = rebase_path(out.environment.texture, from, to);
  return out;
}

Scene load_project_text(const std::string& text, const std::string& file_label,
                        const fs::path& base_dir, bool check_files) {
  return scene_from_json(json_fields::parse_text(text, file_label), file_label, base_dir,
                         check_files);
}

// The JSON path of the first string of the scene that is not valid UTF-8, or "".
std::string first_non_utf8_string(const Scene& s) {
  using json_fields::is_valid_utf8;
  if (!is_valid_utf8(s.environment.texture)) return "environment.texture";
  for (size_t i = 0; i < s.textures.size(); ++i)
    for (const auto& [key, text] : {std::pair{"name", &s.textures[i].name}, std::pair{"path", &s.textures[i].path}})
      if (!is_valid_utf8(*text)) return child_path(index_path("textures", i), key);
  for (size_t i = 0; i < s.materials.size(); ++i) {
    const Material& m = s.materials[i];
    for (const auto& [key, text] :
         {std::pair{"name", &m.name}, std::pair{"color_texture", &m.color_texture},
          std::pair{"emission_texture", &m.emission_texture},
          std::pair{"roughness_texture", &m.roughness_texture}})
      if (!is_valid_utf8(*text)) return child_path(index_path("materials", i), key);
  }
  for (size_t i = 0; i < s.spheres.size(); ++i)
    for (const auto& [key, text] : {std::pair{"name", &s.spheres[i].name}, std::pair{"material", &s.spheres[i].material}})
      if (!is_valid_utf8(*text)) return child_path(index_path("spheres", i), key);
  for (size_t i = 0; i < s.quads.size(); ++i)
    for (const auto& [key, text] : {std::pair{"name", &s.quads[i].name}, std::pair{"material", &s.quads[i].material}})
      if (!is_valid_utf8(*text)) return child_path(index_path("quads", i), key);
  return "";
}

static std::string project_size_problem(uintmax_t size) {
  return "file is too large (" + std::to_string(size) + " bytes, the limit is " +
         std::to_string(kMaxProjectBytes) + " = " + bytes_text(double(kMaxProjectBytes)) + ")";
}

Scene load_project(const fs::path& file) {
  const std::string label = file.string();
  std::error_code ec;
  if (!fs::exists(file, ec) && !ec) throw ProjectError(label, "", "no such file");
  if (fs::is_directory(file, ec)) throw ProjectError(label, "", "is a folder, not a project file");
  // A FIFO or device (a project named /dev/zero, or a link to it) would block or never end.
  const bool regular = fs::is_regular_file(file, ec);
  if (ec) throw ProjectError(label, "", "cannot open: " + ec.message());  // a symlink loop, say
  if (!regular) throw ProjectError(label, "", "not a regular file (a device, FIFO or socket)");
  const auto size = fs::file_size(file, ec);
  if (!ec && size > kMaxProjectBytes) throw ProjectError(label, "", project_size_problem(size));
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ProjectError(label, "", std::string("cannot open: ") + std::strerror(errno));
  // Read at most one byte past the limit: the file may grow after file_size.
  std::string text;
  text.reserve(ec ? 0 : static_cast<size_t>(size));
  char buffer[65536];
  while (text.size() <= kMaxProjectBytes && in.read(buffer, sizeof buffer).gcount() > 0)
    text.append(buffer, static_cast<size_t>(in.gcount()));
  if (in.bad()) throw ProjectError(label, "", "cannot read the file");
  if (text.size() > kMaxProjectBytes) throw ProjectError(label, "", project_size_problem(text.size()));
  try {
    return load_project_text(text, label, fs::absolute(file).parent_path(), true);
  } catch (const ProjectError&) {
    throw;
  } catch (const std::exception& e) {  // a safety net: nothing else escapes as another type
    throw ProjectError(label, "", e.what());
  }
}

std::string save_project_text(const Scene& scene, const fs::path& file) {
  const std::string label = file.string();
  try {
    const Scene rebased = rebase_asset_paths(scene, fs::absolute(file).parent_path());
    // JSON text is UTF-8: a path from a folder named in another encoding cannot be stored.
    if (const std::string bad = first_non_utf8_string(rebased); !bad.empty())
      throw ProjectError(label, bad, "is not valid UTF-8, which a JSON file cannot hold "
                                     "(rename the file or folder)");
    return project_file_text(rebased);
  } catch (const ProjectError&) {
    throw;
  } catch (const std::exception& e) {  // invalid UTF-8 in a name, or a filesystem error
    throw ProjectError(label, "", std::string("cannot write the scene: ") + e.what());
  }
}

void save_project(const Scene& scene, const fs::path& file) {
  const std::string text = save_project_text(scene, file);
  try {
    write_file_atomically(file, text.data(), text.size());
  } catch (const FileWriteError& e) {
    throw ProjectError(file.string(), "", e.problem);
  }
}

}  // namespace glint
