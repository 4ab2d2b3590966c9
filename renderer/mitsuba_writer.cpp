// Glint scene -> Mitsuba 3 XML. The conventions (bench/tools/mitsuba_export.py, validated by the
// accuracy bench, bench/reports/RESULTS.md):
// - Glint shades both sides of a surface: opaque materials are wrapped in twosided; glass is not
//   (Mitsuba refuses it: thindielectric is symmetric, and a dielectric is one interface with its
//   inside opposite the quad's normal or inside the sphere).
// - Emission leaves both sides in Glint, the front only in Mitsuba: an emissive quad gets a
//   back copy facing the other way a hair behind it, and an emissive sphere with the camera or
//   a shape inside gets an inward-facing inner copy (ids glint-back-of-quad-N,
//   glint-inside-of-sphere-N, which the reader leaves out).
// - Roughness r is GGX alpha r^2. The camera is look_at with fov_axis y; the environment's
//   to_world is a rotation about +Y by rotation_deg - 90.
#include <cmath>
#include <set>

#include "renderer/json_fields.h"
#include "renderer/mitsuba_scene.h"
#include "renderer/quad_shape.h"

namespace glint {

namespace {

using json_fields::float_text;

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      case '\n': out += "&#10;"; break;
      case '\t': out += "&#9;"; break;
      case '\r': out += "&#13;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string vec_text(glm::vec3 v) { return float_text(v.x) + ", " + float_text(v.y) + ", " + float_text(v.z); }
std::string number(double v) { return float_text(static_cast<float>(v)); }

// A 4x4 matrix, row by row, from columns x, y, z and the origin.
std::string matrix_text(const glm::dvec3& x, const glm::dvec3& y, const glm::dvec3& z, const glm::dvec3& o) {
  std::string t;
  for (int r = 0; r < 3; ++r)
    t += number(x[r]) + " " + number(y[r]) + " " + number(z[r]) + " " + number(o[r]) + (r < 2 ? "  " : "");
  return t + "  0 0 0 1";
}

bool is_white(glm::vec3 c) { return c == glm::vec3(1.0f); }
bool emits(const Material& m) { return m.emission != glm::vec3(0.0f); }

class MitsubaWriter {
 public:
  MitsubaWriter(const Scene& scene, const std::string& stem, const ExportOptions& options)
      : scene_(scene), stem_(stem), options_(options) {}

  ExportedScene write() {
    out_.text = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
                "<!-- Written by glint convert (Mitsuba 3; docs/DESIGN.md, Scene exchange). -->\n"
                "<scene version=\"3.0.0\">\n";
    defaults();
    camera();
    for (const Texture& t : scene_.textures) used_ids_.insert(texture_id(t.name));
    for (const Material& m : scene_.materials) used_ids_.insert(m.name);
    textures();
    for (const Material& m : scene_.materials) material(m);
    for (size_t i = 0; i < scene_.spheres.size(); ++i) sphere(i);
    for (size_t i = 0; i < scene_.quads.size(); ++i) quad(i);
    environment();
    out_.text += "</scene>\n";
    return std::move(out_);
  }

 private:
  void line(const std::string& text, int indent = 1) { out_.text += std::string(2 * indent, ' ') + text + "\n"; }
  void warn(const std::string& text) { out_.warnings.push_back(text); }
  static std::string texture_id(const std::string& name) { return "texture:" + name; }

  void defaults() {
    line("<default name=\"spp\" value=\"" + std::to_string(options_.samples_per_pixel) + "\"/>");
    line("<default name=\"seed\" value=\"" + std::to_string(scene_.render.seed) + "\"/>");
    line("<default name=\"resx\" value=\"" + std::to_string(scene_.film.width) + "\"/>");
    line("<default name=\"resy\" value=\"" + std::to_string(scene_.film.height) + "\"/>");
    if (!scene_.environment.texture.empty())
      line("<default name=\"envmap\" value=\"" + escape(scene_.environment.texture) + "\"/>");
    line("<integrator type=\"path\">");
    line("<integer name=\"max_depth\" value=\"" + std::to_string(scene_.render.max_bounces + 1) + "\"/>", 2);
    line("</integrator>");
    if (scene_.display != DisplaySettings{})
      warn("display: exposure and tone curve are not written (Mitsuba's film holds linear radiance)");
  }

  double scene_size() const {
    glm::dvec3 lo(scene_.camera.position), hi(scene_.camera.position);
    auto grow = [&](glm::dvec3 p) { lo = glm::min(lo, p); hi = glm::max(hi, p); };
    for (const Sphere& s : scene_.spheres) {
      grow(glm::dvec3(s.center) - double(s.radius));
      grow(glm::dvec3(s.center) + double(s.radius));
    }
    for (const Quad& q : scene_.quads)
      for (const glm::vec3& c : q.corners) grow(glm::dvec3(c));
    const glm::dvec3 d = hi - lo;
    const double size = std::max(d.x, std::max(d.y, d.z));
    return size > 0 ? size : 1.0;
  }

  void camera() {
    const Camera& c = scene_.camera;
    const bool lens = c.aperture_radius > 0;
    if (c.aperture_radius == 0 && std::abs(c.focus_distance - glm::length(c.target - c.position)) > 1e-5f * c.focus_distance)
      warn("camera: the focus distance of a pinhole camera is not written (it has no effect; the target's distance is read back)");
    line(std::string("<sensor type=\"") + (lens ? "thinlens" : "perspective") + "\">");
    line("<string name=\"fov_axis\" value=\"y\"/>", 2);
    line("<float name=\"fov\" value=\"" + float_text(c.vfov_deg) + "\"/>", 2);
    const double size = scene_size();
    line("<float name=\"near_clip\" value=\"" + number(1e-6 * size) + "\"/>", 2);
    line("<float name=\"far_clip\" value=\"" + number(1e3 * size + 1e6) + "\"/>", 2);
    if (lens) {
      line("<float name=\"aperture_radius\" value=\"" + float_text(c.aperture_radius) + "\"/>", 2);
      line("<float name=\"focus_distance\" value=\"" + float_text(c.focus_distance) + "\"/>", 2);
    }
    line("<transform name=\"to_world\">", 2);
    line("<lookat origin=\"" + vec_text(c.position) + "\" target=\"" + vec_text(c.target) + "\" up=\"" +
             vec_text(c.up) + "\"/>", 3);
    line("</transform>", 2);
    line("<sampler type=\"independent\">", 2);
    line("<integer name=\"sample_count\" value=\"$spp\"/>", 3);
    line("<integer name=\"seed\" value=\"$seed\"/>", 3);
    line("</sampler>", 2);
    line("<film type=\"hdrfilm\">", 2);
    line("<integer name=\"width\" value=\"$resx\"/>", 3);
    line("<integer name=\"height\" value=\"$resy\"/>", 3);
    line("<string name=\"pixel_format\" value=\"rgb\"/>", 3);
    line("<string name=\"component_format\" value=\"float32\"/>", 3);
    line("<rfilter type=\"box\"/>", 3);
    line("</film>", 2);
    line("</sensor>");
  }

  void textures() {
    std::set<std::string> used;
    for (const Material& m : scene_.materials)
      if (!m.color_texture.empty()) used.insert(m.color_texture);
    for (const Texture& t : scene_.textures) {
      if (!used.count(t.name)) continue;  // roughness and emission textures are not written
      line("<texture type=\"bitmap\" id=\"" + escape(texture_id(t.name)) + "\">");
      line("<string name=\"filename\" value=\"" + escape(t.path) + "\"/>", 2);
      line("</texture>");
    }
  }

  // `name`'s colour: an rgb value, or a reference to the colour texture.
  void colour(const Material& m, const std::string& name, int indent) {
    if (m.color_texture.empty()) {
      line("<rgb name=\"" + name + "\" value=\"" + vec_text(m.color) + "\"/>", indent);
      return;
    }
    line("<ref name=\"" + name + "\" id=\"" + escape(texture_id(m.color_texture)) + "\"/>", indent);
    if (!is_white(m.color))
      warn("material " + json_fields::quote_name(m.name) + ": its colour (" + vec_text(m.color) +
           ") is not written: Mitsuba's bitmap texture has no tint");
  }

  void roughness(const Material& m, int indent) {
    line("<string name=\"distribution\" value=\"ggx\"/>", indent);
    line("<float name=\"alpha\" value=\"" + number(double(m.roughness) * m.roughness) + "\"/>", indent);
  }

  // The BSDF element(s) of the material, without the id.
  void bsdf_body(const Material& m, int d) {
    const std::string name = json_fields::quote_name(m.name);
    const bool rough = m.roughness > 0;
    switch (m.type) {
      case MaterialType::matte:
        line("<bsdf type=\"diffuse\">", d);
        colour(m, "reflectance", d + 1);
        break;
      case MaterialType::reflective:
        line(std::string("<bsdf type=\"") + (rough ? "roughconductor" : "conductor") + "\">", d);
        line("<string name=\"material\" value=\"none\"/>", d + 1);
        colour(m, "specular_reflectance", d + 1);
        if (rough) roughness(m, d + 1);
        if (!is_white(m.color) || !m.color_texture.empty())
          warn("material " + name + ": a coloured mirror reflects Schlick's F(colour) in Glint and the constant colour in Mitsuba (they differ towards grazing angles)");
        break;
      case MaterialType::glossy:
        line(std::string("<bsdf type=\"") + (rough ? "roughplastic" : "plastic") + "\">", d);
        colour(m, "diffuse_reflectance", d + 1);
        line("<float name=\"int_ior\" value=\"" + float_text(m.ior) + "\"/>", d + 1);
        line("<float name=\"ext_ior\" value=\"1\"/>", d + 1);
        if (rough) roughness(m, d + 1);
        warn("material " + name + ": glossy is written as Mitsuba's " + (rough ? "roughplastic" : "plastic") +
             ", which splits coat and base differently (renders differ)");
        break;
      case MaterialType::transparent:
        line("<bsdf type=\"thindielectric\">", d);
        line("<float name=\"int_ior\" value=\"" + float_text(m.ior) + "\"/>", d + 1);
        line("<float name=\"ext_ior\" value=\"1\"/>", d + 1);
        colour(m, "specular_transmittance", d + 1);
        if (rough) warn("material " + name + ": the roughness of thin glass (" + float_text(m.roughness) + ") is not written: Mitsuba's thindielectric is smooth");
        warn("material " + name + ": transparent is written as Mitsuba's thindielectric (exact Fresnel with inter-reflections where Glint uses Schlick's; renders differ)");
        break;
      case MaterialType::refractive: {
        const bool frosted = m.roughness >= 0.03f;
        line(std::string("<bsdf type=\"") + (frosted ? "roughdielectric" : "dielectric") + "\">", d);
        line("<float name=\"int_ior\" value=\"" + float_text(m.ior) + "\"/>", d + 1);
        line("<float name=\"ext_ior\" value=\"1\"/>", d + 1);
        colour(m, "specular_transmittance", d + 1);
        if (frosted) {
          roughness(m, d + 1);
          line("<boolean name=\"sample_visible\" value=\"true\"/>", d + 1);
        } else if (m.roughness > 0) {
          warn("material " + name + ": roughness " + float_text(m.roughness) + " is not written (Glint renders solid glass below 0.03 smooth)");
        }
        if (m.ior == 1.0f) warn("material " + name + ": Mitsuba refuses a dielectric of ior 1");
        break;
      }
    }
    line("</bsdf>", d);
  }

  void material(const Material& m) {
    // Glass is not wrapped: Mitsuba's twosided refuses a BSDF that transmits (thindielectric is
    // symmetric anyway, and a dielectric's inside is opposite its normal).
    const bool two_sided = m.type != MaterialType::refractive && m.type != MaterialType::transparent;
    const bool masked = m.opacity < 1;
    int d = 1;
    if (masked) {
      line("<bsdf type=\"mask\" id=\"" + escape(m.name) + "\">", d);
      line("<float name=\"opacity\" value=\"" + float_text(m.opacity) + "\"/>", d + 1);
      ++d;
      if (two_sided) line("<bsdf type=\"twosided\">", d++);
    } else if (two_sided) {
      line("<bsdf type=\"twosided\" id=\"" + escape(m.name) + "\">", d++);
    }
    if (!masked && !two_sided) {
      // The id goes on the BSDF itself: rewrite its opening line after writing it.
      const size_t at = out_.text.size();
      bsdf_body(m, d);
      const size_t close = out_.text.find('>', at);
      out_.text.insert(close, " id=\"" + escape(m.name) + "\"");
    } else {
      bsdf_body(m, d);
    }
    while (d > 1) line("</bsdf>", --d);
    if (!m.emission_texture.empty())
      warn("material " + json_fields::quote_name(m.name) + ": its emission texture is not written (Mitsuba's area light has no tint for it)");
    if (!m.roughness_texture.empty())
      warn("material " + json_fields::quote_name(m.name) + ": its roughness texture is not written (Glint's alpha is (roughness x texture)^2, which Mitsuba's alpha texture cannot express)");
  }

  void emitter(const Material& m, int d) {
    line("<emitter type=\"area\">", d);
    line("<rgb name=\"radiance\" value=\"" + vec_text(m.emission) + "\"/>", d + 1);
    line("</emitter>", d);
  }

  // ` id="NAME"` when the name can be a Mitsuba id (unique in the file), else "".
  std::string shape_id(const std::string& name, const char* kind, size_t index) {
    if (name.empty()) return "";
    if (used_ids_.insert(name).second) return " id=\"" + escape(name) + "\"";
    warn(std::string(kind) + "s[" + std::to_string(index) + "]: its name " + json_fields::quote_name(name) +
         " is not written: it repeats another name, and Mitsuba's ids are unique");
    return "";
  }

  const Material& material_of(const std::string& name) const {
    static const Material fallback;
    const int i = find_material(scene_, name);
    return i >= 0 ? scene_.materials[i] : fallback;
  }

  void sphere(size_t i) {
    const Sphere& s = scene_.spheres[i];
    const Material& m = material_of(s.material);
    line("<shape type=\"sphere\"" + shape_id(s.name, "sphere", i) + ">");
    sphere_placement(s, s.radius, 2);
    line("<ref id=\"" + escape(s.material) + "\"/>", 2);
    if (emits(m)) emitter(m, 2);
    line("</shape>");
    if (emits(m) && something_inside(i)) {
      line("<shape type=\"sphere\" id=\"glint-inside-of-sphere-" + std::to_string(i) + "\">");
      sphere_placement(s, s.radius * (1 - 1e-5), 2);
      line("<boolean name=\"flip_normals\" value=\"true\"/>", 2);
      line("<ref id=\"" + escape(s.material) + "\"/>", 2);
      emitter(m, 2);
      line("</shape>");
    }
  }

  // Centre and radius; for a textured material a to_world whose local +Z is world +Y and local
  // +Y world +Z, so that Mitsuba's uv (atan2(y, x), acos(z)) is Glint's (atan2(n.z, n.x), acos(n.y)).
  void sphere_placement(const Sphere& s, double radius, int d) {
    if (material_of(s.material).color_texture.empty()) {
      line("<point name=\"center\" value=\"" + vec_text(s.center) + "\"/>", d);
      line("<float name=\"radius\" value=\"" + number(radius) + "\"/>", d);
      return;
    }
    line("<transform name=\"to_world\">", d);
    line("<matrix value=\"" + matrix_text({radius, 0, 0}, {0, 0, radius}, {0, radius, 0}, glm::dvec3(s.center)) + "\"/>", d + 1);
    line("</transform>", d);
  }

  bool something_inside(size_t i) const {
    const Sphere& s = scene_.spheres[i];
    auto inside = [&](glm::vec3 p) { return glm::length(glm::dvec3(p) - glm::dvec3(s.center)) < s.radius; };
    if (inside(scene_.camera.position)) return true;
    for (size_t j = 0; j < scene_.spheres.size(); ++j)
      if (j != i && inside(scene_.spheres[j].center)) return true;
    for (const Quad& q : scene_.quads)
      for (const glm::vec3& c : q.corners)
        if (inside(c)) return true;
    return false;
  }

  void quad(size_t i) {
    const Quad& q = scene_.quads[i];
    const Material& m = material_of(q.material);
    const bool rectangle = quad_is_parallelogram(q.corners) && exchange::has_default_uvs(q);
    const std::string id = shape_id(q.name, "quad", i);
    if (rectangle) {
      const exchange::QuadFrame f = exchange::quad_frame(q.corners);
      line("<shape type=\"rectangle\"" + id + ">");
      line("<transform name=\"to_world\">", 2);
      line("<matrix value=\"" + matrix_text(f.x, f.y, f.z, f.origin) + "\"/>", 3);
      line("</transform>", 2);
    } else {
      const std::string path = stem_ + "-meshes/quad-" + std::to_string(i) + ".obj";
      out_.side_files.push_back({path, obj_text(q, false)});
      line("<shape type=\"obj\"" + id + ">");
      line("<string name=\"filename\" value=\"" + escape(path) + "\"/>", 2);
      line("<boolean name=\"face_normals\" value=\"true\"/>", 2);
      line("<boolean name=\"flip_tex_coords\" value=\"false\"/>", 2);
    }
    line("<ref id=\"" + escape(q.material) + "\"/>", 2);
    if (emits(m)) emitter(m, 2);
    line("</shape>");
    if (emits(m)) back_copy(i, q, m);
  }

  // The emitting back of a quad: the same quad facing the other way, a hair behind it.
  void back_copy(size_t i, const Quad& q, const Material& m) {
    const glm::dvec3 n = exchange::quad_frame(q.corners).z;
    double extent = 0;
    for (const glm::vec3& c : q.corners) extent = std::max(extent, double(glm::max(glm::abs(c).x, glm::max(glm::abs(c).y, glm::abs(c).z))));
    const double eps = 1e-5 * (1 + extent);
    Quad back = q;
    for (glm::vec3& c : back.corners) c = glm::vec3(glm::dvec3(c) - eps * n);
    const std::string path = stem_ + "-meshes/quad-" + std::to_string(i) + "-back.obj";
    out_.side_files.push_back({path, obj_text(back, true)});
    line("<shape type=\"obj\" id=\"glint-back-of-quad-" + std::to_string(i) + "\">");
    line("<string name=\"filename\" value=\"" + escape(path) + "\"/>", 2);
    line("<boolean name=\"face_normals\" value=\"true\"/>", 2);
    line("<boolean name=\"flip_tex_coords\" value=\"false\"/>", 2);
    line("<ref id=\"" + escape(q.material) + "\"/>", 2);
    emitter(m, 2);
    line("</shape>");
  }

  // Glint's triangles (p0, p1, p2) and (p1, p3, p2) (reversed for a back copy), uvs as they are.
  static std::string obj_text(const Quad& q, bool reversed) {
    std::string t = "# A Glint quad: corners p0 p1 p2 p3, triangles p0 p1 p2 and p1 p3 p2\n";
    for (const glm::vec3& c : q.corners) t += "v " + float_text(c.x) + " " + float_text(c.y) + " " + float_text(c.z) + "\n";
    for (const glm::vec2& uv : q.uvs) t += "vt " + float_text(uv.x) + " " + float_text(uv.y) + "\n";
    t += reversed ? "f 1/1 3/3 2/2\nf 2/2 3/3 4/4\n" : "f 1/1 2/2 3/3\nf 2/2 4/4 3/3\n";
    return t;
  }

  void environment() {
    const Environment& e = scene_.environment;
    if (!e.texture.empty()) {
      line("<emitter type=\"envmap\">");
      line("<string name=\"filename\" value=\"$envmap\"/>", 2);
      line("<float name=\"scale\" value=\"" + float_text(e.intensity) + "\"/>", 2);
      line("<transform name=\"to_world\">", 2);
      line("<rotate y=\"1\" angle=\"" + number(double(e.rotation_deg) - 90.0) + "\"/>", 3);
      line("</transform>", 2);
      line("</emitter>");
      warn("environment: Mitsuba's envmap puts the image's first and last rows on the poles, Glint half a texel "
           "inside them (bench/tools/mitsuba_export.py passes a resampled image as the envmap parameter where the "
           "match must be exact)");
      return;
    }
    const glm::vec3 radiance = e.color * e.intensity;
    if (radiance == glm::vec3(0.0f)) return;
    line("<emitter type=\"constant\">");
    line("<rgb name=\"radiance\" value=\"" + vec_text(radiance) + "\"/>", 2);
    line("</emitter>");
  }

  const Scene& scene_;
  std::string stem_;
  ExportOptions options_;
  ExportedScene out_;
  std::set<std::string> used_ids_;
};

}  // namespace

ExportedScene write_mitsuba_scene(const Scene& scene, const std::string& stem, const ExportOptions& options) {
  return MitsubaWriter(scene, stem, options).write();
}

}  // namespace glint
