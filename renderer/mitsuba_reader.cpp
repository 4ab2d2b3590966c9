// Mitsuba 3 XML -> Glint scene: the inverse of mitsuba_writer.cpp's conventions, and the
// common subset of other scenes (their defaults where a property is absent). A property that
// is read nowhere is named in a warning; shapes Glint does not model are counted in one.
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/json_fields.h"
#include "renderer/mitsuba_scene.h"
#include "renderer/mitsuba_values.h"
#include "renderer/obj_mesh.h"
#include "renderer/scene_fields.h"
#include "renderer/state_file.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

using mitsuba::Props;

constexpr const char* kBackCopy = "glint-back-of-quad-";
constexpr const char* kInnerCopy = "glint-inside-of-sphere-";
constexpr const char* kTextureIdPrefix = "texture:";

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

class MitsubaReader {
 public:
  MitsubaReader(const std::string& file, const fs::path& base) : ctx_{file, {}, {}}, base_(base) {
    scene_.environment.color = glm::vec3(0);  // no emitter: a black background
  }

  ImportedScene read(const XmlElement& root) {
    if (root.name != "scene") ctx_.fail(root, "the root element must be <scene>");
    for (const XmlElement& e : root.children) {
      const std::string* id = e.attribute("id");
      if (e.name == "default") {
        const std::string name = ctx_.required(e, "name");
        if (!ctx_.defaults.count(name)) ctx_.defaults[name] = ctx_.required(e, "value");
      } else if (id && e.name == "texture") {
        textures_[*id] = &e;
      }
    }
    for (const XmlElement& e : root.children) top_level(e);
    ctx_.warn_counts("not imported (Glint models spheres and quads): ", skipped_shapes_);
    ctx_.warn_counts("not imported (Glint's lights are emissive surfaces and the environment): ", skipped_emitters_);
    if (emitting_quads_ > back_copies_)
      ctx_.warnings.push_back(ctx_.file + ": " + exchange::count_text(emitting_quads_ - back_copies_, "area light") +
                              " on quads without a back copy emit from both sides in Glint, from the front only in Mitsuba");
    return {std::move(scene_), std::move(ctx_.warnings)};
  }

 private:
  void top_level(const XmlElement& e) {
    if (e.name == "bsdf" && e.attribute("id")) return top_level_bsdf(e);
    if (e.name == "default" || e.name == "bsdf" || e.name == "texture") {
      if (e.name != "default" && !e.attribute("id")) ctx_.warn(e, "not imported: it has no id for a shape to use");
      return;
    }
    if (e.name == "integrator") return integrator(e);
    if (e.name == "sensor") return sensor(e);
    if (e.name == "shape") return shape(e);
    if (e.name == "emitter") return emitter(e);
    if (e.name == "include") ctx_.fail(e, "<include> is not supported: merge the files into one");
    ctx_.warn(e, "not imported");
  }

  void integrator(const XmlElement& e) {
    Props p(ctx_, e);
    const std::string type = p.type();
    if (type != "path" && type != "volpath") {
      ctx_.warn(e, "read as Glint's path tracer (max_bounces " + std::to_string(scene_.render.max_bounces) + ")");
      return;
    }
    const long depth = p.integer("max_depth", -1);
    if (depth < 0 || depth - 1 > kMaxBounces) {
      scene_.render.max_bounces = kMaxBounces;
      ctx_.warn(e, "max_depth " + std::to_string(depth) + " is read as Glint's largest max_bounces, " + std::to_string(kMaxBounces));
    } else {
      scene_.render.max_bounces = depth == 0 ? 0 : int(depth - 1);
      if (depth == 0) ctx_.warn(e, "max_depth 0 (nothing visible) is read as max_bounces 0");
    }
    p.skip({"hide_emitters", "rr_depth"});
    p.finish();
  }

  void sensor(const XmlElement& e) {
    Props p(ctx_, e);
    const std::string type = p.type();
    if (type != "perspective" && type != "thinlens") ctx_.warn(e, "read as a perspective camera");
    Camera& c = scene_.camera;
    if (const XmlElement* film = p.child("film")) read_film(*film);
    if (const XmlElement* sampler = p.child("sampler")) read_sampler(*sampler);
    const double fov = p.number("fov", 39.3077);
    const std::string axis = p.string("fov_axis", "x");
    c.vfov_deg = float(mitsuba::vertical_fov(fov, axis, scene_.film.width, scene_.film.height, ctx_, e));
    if (type == "thinlens") {
      c.aperture_radius = float(p.number("aperture_radius", 0));
      c.focus_distance = float(p.number("focus_distance", 0));
    }
    if (const XmlElement* t = p.transform("to_world")) camera_transform(*t);
    if (type != "thinlens") c.focus_distance = glm::length(c.target - c.position);
    p.skip({"near_clip", "far_clip"});
    p.finish();
  }

  void camera_transform(const XmlElement& t) {
    Camera& c = scene_.camera;
    if (t.children.size() == 1 && t.children[0].name == "lookat") {
      Props l(ctx_, t.children[0]);
      c.position = l.attribute_vec3("origin");
      c.target = l.attribute_vec3("target");
      c.up = l.attribute_vec3("up", glm::vec3(0, 1, 0));
      return;
    }
    const glm::dmat4 m = mitsuba::transform(ctx_, t);
    const glm::dvec3 left(m[0]), up(m[1]), dir(m[2]);
    c.position = glm::vec3(m[3]);
    c.target = glm::vec3(glm::dvec3(m[3]) + glm::normalize(dir) * double(c.focus_distance > 0 ? c.focus_distance : 1.0f));
    c.up = glm::vec3(glm::normalize(up));
    if (glm::dot(glm::cross(left, up), dir) < 0)
      ctx_.warn(t, "the camera's transform mirrors the image, which Glint's camera cannot: the image is mirrored left to right");
  }

  void read_film(const XmlElement& e) {
    Props p(ctx_, e);
    if (p.type() != "hdrfilm") ctx_.warn(e, "read as Glint's film (linear radiance)");
    scene_.film.width = int(p.integer("width", 768));
    scene_.film.height = int(p.integer("height", 576));
    if (const XmlElement* f = p.child("rfilter")) {
      Props filter(ctx_, *f);
      if (filter.type() != "box") ctx_.warn(*f, "Glint filters with a box of one pixel");
      filter.finish();
    } else {
      ctx_.warn(e, "Mitsuba's default filter (gaussian) is read as Glint's box of one pixel");
    }
    p.skip({"pixel_format", "component_format", "file_format"});
    p.finish();
  }

  void read_sampler(const XmlElement& e) {
    Props p(ctx_, e);
    p.type();
    const long count = p.integer("sample_count", 4);
    scene_.render.seed = uint32_t(p.integer("seed", 0));
    ctx_.warn(e, "its " + std::to_string(count) + " samples per pixel are not part of a Glint scene (glint render --spp)");
    p.finish();
  }

  void emitter(const XmlElement& e) {
    Props p(ctx_, e);
    const std::string type = p.type();
    Environment& env = scene_.environment;
    if (type == "constant" || type == "envmap") {
      if (has_environment_) ctx_.warn(e, "a second environment replaces the first (Glint has one)");
      has_environment_ = true;
    }
    if (type == "constant") {
      env = Environment{};
      env.color = p.colour("radiance", glm::vec3(1));
    } else if (type == "envmap") {
      env = Environment{};
      env.color = glm::vec3(1);
      env.texture = p.string("filename", "");
      if (env.texture.empty()) ctx_.fail(e, "an envmap needs a filename");
      env.intensity = float(p.number("scale", 1));
      if (const XmlElement* t = p.transform("to_world")) env.rotation_deg = float(mitsuba::y_rotation_deg(ctx_, *t) + 90.0);
      else env.rotation_deg = 90;
    } else {
      ++skipped_emitters_["<emitter type=\"" + type + "\">"];
      return;
    }
    p.finish();
  }

  // ---- Shapes ----

  void shape(const XmlElement& e) {
    Props p(ctx_, e);
    const std::string type = p.type();
    const std::string* id = e.attribute("id");
    if (id && (starts_with(*id, kBackCopy) || starts_with(*id, kInnerCopy))) {
      back_copies_ += starts_with(*id, kBackCopy);
      return;  // the writer's two-sided emission, already in the original shape
    }
    const std::string name = id ? *id : "";
    if (type == "sphere") return sphere(p, name);
    if (type == "rectangle" || type == "obj") return quad(p, name, type == "obj");
    ++skipped_shapes_["<shape type=\"" + type + "\">"];
  }

  // A top-level BSDF as a Glint material of its id, in the file's order (unused ones too).
  void top_level_bsdf(const XmlElement& e) {
    Material m = mitsuba::read_bsdf(ctx_, e, [&](const XmlElement& t) { return texture(t); });
    m.name = unique_material_name(*e.attribute("id"));
    scene_.materials.push_back(m);
    bsdf_materials_[*e.attribute("id")] = m.name;
  }

  std::string unique_material_name(const std::string& wanted) const {
    std::string name = wanted;
    for (int n = 2; find_material(scene_, name) >= 0; ++n) name = wanted + "-" + std::to_string(n);
    return name;
  }

  // The shape's material: a <ref> to a top-level BSDF or an inline one, with the shape's area
  // emitter. Glint keeps emission in the material: the first shape to use a BSDF gives its
  // material the emission, a shape with another emission gets a copy ("NAME-2").
  std::string material_of(Props& p) {
    std::string base;
    if (const XmlElement* ref = p.child("ref")) {
      const std::string id = ctx_.required(*ref, "id");
      const auto found = bsdf_materials_.find(id);
      if (found == bsdf_materials_.end()) ctx_.fail(*ref, "no <bsdf id=\"" + json_fields::clip(id, 60) + "\"> precedes it");
      base = found->second;
    } else if (const XmlElement* bsdf = p.child("bsdf")) {
      Material m = mitsuba::read_bsdf(ctx_, *bsdf, [&](const XmlElement& t) { return texture(t); });
      m.name = base = unique_material_name(bsdf->attribute("id") ? *bsdf->attribute("id") : "material");
      scene_.materials.push_back(m);
    } else {
      base = "default";  // Mitsuba's default BSDF: a diffuse of reflectance 0.5
      if (find_material(scene_, base) < 0) scene_.materials.push_back(Material{base, MaterialType::matte, glm::vec3(0.5f)});
    }
    glm::vec3 emission(0);
    if (const XmlElement* em = p.child("emitter")) {
      Props ep(ctx_, *em);
      if (ep.type() != "area") ctx_.warn(*em, "not imported (a shape's emitter must be an area light)");
      else emission = ep.colour("radiance", glm::vec3(1));
      ep.finish();
    }
    const auto known = materials_.find({base, emission});
    if (known != materials_.end()) return known->second;
    Material& m = scene_.materials[find_material(scene_, base)];
    if (!claimed_.count(base)) {
      claimed_.insert(base);
      m.emission = emission;
      return materials_[{base, emission}] = base;
    }
    Material copy = m;
    copy.emission = emission;
    copy.name = unique_material_name(base);
    scene_.materials.push_back(copy);
    return materials_[{base, emission}] = copy.name;
  }

  // A Glint texture for a <texture> element or a <ref> to one; its name from the id.
  std::string texture(const XmlElement& e) {
    const XmlElement* t = &e;
    if (e.name == "ref") {
      const std::string id = ctx_.required(e, "id");
      const auto found = textures_.find(id);
      if (found == textures_.end()) ctx_.fail(e, "no <texture id=\"" + json_fields::clip(id, 60) + "\"> precedes it");
      t = found->second;
    }
    Props p(ctx_, *t);
    if (p.type() != "bitmap") {
      ctx_.warn(*t, "not imported (Glint's textures are images)");
      return "";
    }
    const std::string path = p.string("filename", "");
    if (path.empty()) ctx_.fail(*t, "a bitmap texture needs a filename");
    p.skip({"raw", "filter_type"});
    p.finish();
    for (const Texture& known : scene_.textures)
      if (known.path == path) return known.name;
    std::string name = t->attribute("id") ? *t->attribute("id") : fs::path(path).stem().string();
    if (starts_with(name, kTextureIdPrefix)) name = name.substr(std::string(kTextureIdPrefix).size());
    for (int n = 2; find_texture(scene_, name) >= 0; ++n) name = fs::path(path).stem().string() + "-" + std::to_string(n);
    scene_.textures.push_back({name, path});
    return name;
  }

  void sphere(Props& p, const std::string& name) {
    Sphere s;
    s.name = name;
    glm::dvec3 center(p.vec3("center", glm::vec3(0)));
    double radius = p.number("radius", 1);
    if (const XmlElement* t = p.transform("to_world")) {
      const glm::dmat4 m = mitsuba::transform(ctx_, *t);
      const double sx = glm::length(glm::dvec3(m[0])), sy = glm::length(glm::dvec3(m[1])), sz = glm::length(glm::dvec3(m[2]));
      if (std::abs(sx - sy) > 1e-5 * sx || std::abs(sx - sz) > 1e-5 * sx) {
        ++skipped_shapes_["ellipsoid (a sphere with a non-uniform scale)"];
        return;
      }
      center = glm::dvec3(m * glm::dvec4(center, 1.0));
      radius *= sx;
    }
    s.center = glm::vec3(center);
    s.radius = float(radius);
    p.skip({"flip_normals"});
    s.material = material_of(p);
    p.finish();
    scene_.spheres.push_back(s);
  }

  void quad(Props& p, const std::string& name, bool mesh) {
    std::optional<Quad> q;
    if (mesh) {
      q = obj_quad(p);
      if (!q) return;
    } else {
      const glm::dmat4 m = p.transform("to_world") ? mitsuba::transform(ctx_, *p.transform("to_world")) : glm::dmat4(1.0);
      auto at = [&](double x, double y) { return glm::vec3(m * glm::dvec4(x, y, 0, 1)); };
      q = Quad{};
      q->corners = {at(-1, -1), at(-1, 1), at(1, -1), at(1, 1)};
      // The rectangle's front is its transformed +Z normal; Glint's is cross(p1 - p0, p2 - p0).
      if (glm::determinant(glm::dmat3(m)) > 0) {
        std::swap(q->corners[1], q->corners[2]);
        std::swap(q->uvs[1], q->uvs[2]);
      }
    }
    q->name = name;
    q->material = material_of(p);
    emitting_quads_ += scene_.materials[find_material(scene_, q->material)].emission != glm::vec3(0);
    p.finish();
    scene_.quads.push_back(*q);
  }

  std::optional<Quad> obj_quad(Props& p) {
    const std::string file = p.string("filename", "");
    if (file.empty()) ctx_.fail(p.element(), "an obj shape needs a filename");
    const fs::path path = fs::path(file).is_absolute() ? fs::path(file) : base_ / file;
    std::optional<std::string> text;
    try {
      text = read_state_file(path, size_t(1) << 30);
    } catch (const StateFileError& e) {
      ctx_.fail(p.element(), path.string() + ": " + e.problem);
    }
    if (!text) ctx_.fail(p.element(), path.string() + ": file not found");
    ObjMesh mesh = parse_obj(*text, path.string());
    const bool flip = p.boolean("flip_tex_coords", true);
    for (glm::vec2& uv : mesh.uvs)
      if (flip) uv.y = 1 - uv.y;
    if (const XmlElement* t = p.transform("to_world")) {
      const glm::dmat4 m = mitsuba::transform(ctx_, *t);
      for (glm::vec3& v : mesh.positions) v = glm::vec3(m * glm::dvec4(v, 1));
    }
    p.skip({"face_normals"});
    std::optional<Quad> q = exchange::quad_from_triangles(mesh.positions, mesh.uvs, mesh.triangles);
    if (!q) {
      ++skipped_shapes_["mesh of " + exchange::count_text(mesh.triangles.size() / 3, "triangle") + " (not a quad)"];
      p.skip_all();
      return std::nullopt;
    }
    if (mesh.has_normals && !p.boolean("face_normals", false))
      ctx_.warn(p.element(), "its vertex normals are not imported (Glint shades quads with their geometric normal)");
    return q;
  }

  mitsuba::Context ctx_;
  fs::path base_;
  Scene scene_;
  std::map<std::string, const XmlElement*> textures_;
  std::map<std::string, std::string> bsdf_materials_;
  std::set<std::string> claimed_;
  std::map<std::pair<std::string, glm::vec3>, std::string, mitsuba::KeyLess> materials_;
  std::map<std::string, size_t> skipped_shapes_, skipped_emitters_;
  size_t emitting_quads_ = 0, back_copies_ = 0;
  bool has_environment_ = false;
};

}  // namespace

ImportedScene read_mitsuba_scene(const std::string& text, const std::string& file_label, const fs::path& base_dir) {
  const XmlElement root = parse_xml(text, file_label);
  return MitsubaReader(file_label, base_dir).read(root);
}

}  // namespace glint
