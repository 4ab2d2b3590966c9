// Glint scene -> pbrt-v4 scene file. The conventions (renderer/pbrt_scene.h):
// - pbrt's camera space is left-handed: "Scale -1 1 1" before LookAt keeps Glint's image
//   unmirrored. pbrt's fov is along the shorter image axis, Glint's vfov along the vertical.
// - Roughness r is GGX alpha r^2, written as "roughness" with remaproughness false. Solid glass
//   below r = 0.03 is smooth in Glint; pbrt treats alpha < 1e-3 (r < 0.032) as smooth too.
// - pbrt's image textures look up v flipped (1 - v), so quads' uvs are written as (u, 1 - v);
//   its sphere v runs from the -Z pole, which the flip turns into Glint's v from +Y when the
//   sphere's object space has +Z along world +Y (a mirroring transform, with
//   ReverseOrientation to keep the normal outward).
// - Area lights are two-sided, as Glint's emission.
// - A quad is a bilinear patch (p00 p10 p01 p11 = p0 p1 p2 p3: the same boundary and normal
//   cross(p1 - p0, p2 - p0)) when it is a parallelogram with affine uvs, else two triangles.
#include <cmath>
#include <set>

#include "renderer/json_fields.h"
#include "renderer/pbrt_scene.h"
#include "renderer/quad_shape.h"

namespace glint {

namespace {

using json_fields::float_text;

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') { out += "\\n"; continue; }
    out += c;
  }
  return out + "\"";
}
std::string num(double v) { return float_text(static_cast<float>(v)); }
std::string vec(glm::vec3 v) { return float_text(v.x) + " " + float_text(v.y) + " " + float_text(v.z); }
bool is_white(glm::vec3 c) { return c == glm::vec3(1.0f); }

// uv3 = uv1 + uv2 - uv0: the quad's uvs are an affine map of its parallelogram.
bool affine_uvs(const Quad& q) { return q.uvs[3] == q.uvs[1] + q.uvs[2] - q.uvs[0]; }

class PbrtWriter {
 public:
  PbrtWriter(const Scene& scene, const ExportOptions& options) : scene_(scene), options_(options) {}

  ExportedScene write() {
    out_.text = "# Written by glint convert (pbrt-v4; docs/DESIGN.md, Scene exchange).\n";
    camera();
    out_.text += "WorldBegin\n\n";
    environment();
    textures();
    for (const Material& m : scene_.materials) material(m);
    out_.text += "\n";
    for (const Sphere& s : scene_.spheres) sphere(s);
    for (const Quad& q : scene_.quads) quad(q);
    return std::move(out_);
  }

 private:
  void warn(const std::string& text) { out_.warnings.push_back(text); }
  void add(const std::string& text) { out_.text += text + "\n"; }

  void camera() {
    const Camera& c = scene_.camera;
    const Film& f = scene_.film;
    if (c.aperture_radius == 0 && std::abs(c.focus_distance - glm::length(c.target - c.position)) > 1e-5f * c.focus_distance)
      warn("camera: the focus distance of a pinhole camera is not written (it has no effect; the target's distance is read back)");
    double fov = c.vfov_deg;
    if (f.height > f.width)  // pbrt's fov spans the shorter axis, here the horizontal one
      fov = glm::degrees(2 * std::atan(std::tan(glm::radians(double(c.vfov_deg)) / 2) * f.width / f.height));
    add("Scale -1 1 1  # pbrt's camera space is left-handed; Glint's world is right-handed");
    add("LookAt " + vec(c.position) + "  " + vec(c.target) + "  " + vec(c.up));
    std::string camera = "Camera \"perspective\" \"float fov\" [ " + num(fov) + " ]";
    if (c.aperture_radius > 0)
      camera += " \"float lensradius\" [ " + float_text(c.aperture_radius) + " ] \"float focaldistance\" [ " +
                float_text(c.focus_distance) + " ]";
    add(camera);
    add("Film \"rgb\" \"integer xresolution\" [ " + std::to_string(f.width) + " ] \"integer yresolution\" [ " +
        std::to_string(f.height) + " ] \"string filename\" [ \"render.exr\" ]");
    add("PixelFilter \"box\" \"float xradius\" [ 0.5 ] \"float yradius\" [ 0.5 ]");
    add("Sampler \"independent\" \"integer pixelsamples\" [ " + std::to_string(options_.samples_per_pixel) +
        " ] \"integer seed\" [ " + std::to_string(scene_.render.seed) + " ]");
    add("Integrator \"path\" \"integer maxdepth\" [ " + std::to_string(scene_.render.max_bounces) + " ]");
    if (scene_.display != DisplaySettings{})
      warn("display: exposure and tone curve are not written (pbrt's film holds linear radiance)");
  }

  void environment() {
    const Environment& e = scene_.environment;
    if (!e.texture.empty()) {
      warn("environment: its lat-long image " + json_fields::quote_name(e.texture) +
           " is not written (pbrt-v4's infinite light takes an equal-area octahedral image); written as the constant colour x intensity");
    }
    const glm::vec3 radiance = e.color * e.intensity;
    if (radiance != glm::vec3(0.0f)) add("LightSource \"infinite\" \"rgb L\" [ " + vec(radiance) + " ]");
  }

  void textures() {
    std::set<std::string> used;
    for (const Material& m : scene_.materials)
      if (!m.color_texture.empty()) used.insert(m.color_texture);
    for (const Texture& t : scene_.textures)
      if (used.count(t.name))
        add("Texture " + quoted(t.name) + " \"spectrum\" \"imagemap\" \"string filename\" [ " + quoted(t.path) + " ]");
  }

  std::string colour(const Material& m, const std::string& name) {
    if (m.color_texture.empty()) return " \"rgb " + name + "\" [ " + vec(m.color) + " ]";
    if (!is_white(m.color))
      warn("material " + json_fields::quote_name(m.name) + ": its colour (" + vec(m.color) + ") is not written: pbrt's image texture has no tint");
    return " \"texture " + name + "\" " + quoted(m.color_texture);
  }
  static std::string roughness(const Material& m) {
    return " \"float roughness\" [ " + num(double(m.roughness) * m.roughness) + " ] \"bool remaproughness\" false";
  }

  void material(const Material& m) {
    const std::string name = json_fields::quote_name(m.name);
    std::string text = "MakeNamedMaterial " + quoted(m.name) + " \"string type\" ";
    switch (m.type) {
      case MaterialType::matte:
        text += "\"diffuse\"" + colour(m, "reflectance");
        break;
      case MaterialType::reflective:
        text += "\"conductor\"" + colour(m, "reflectance") + roughness(m);
        if (!is_white(m.color) || !m.color_texture.empty())
          warn("material " + name + ": a coloured mirror reflects Schlick's F(colour) in Glint and a metal's exact Fresnel with that reflectance at normal incidence in pbrt (they differ towards grazing angles)");
        break;
      case MaterialType::glossy:
        text += "\"coateddiffuse\"" + colour(m, "reflectance") + roughness(m) + " \"float eta\" [ " + float_text(m.ior) + " ]";
        warn("material " + name + ": glossy is written as pbrt's coateddiffuse, which layers coat and base differently (renders differ)");
        break;
      case MaterialType::transparent:
        text += "\"thindielectric\" \"float eta\" [ " + float_text(m.ior) + " ]";
        if (!is_white(m.color) || !m.color_texture.empty()) warn("material " + name + ": the tint of thin glass is not written (pbrt's thindielectric has none)");
        if (m.roughness > 0) warn("material " + name + ": the roughness of thin glass is not written (pbrt's thindielectric is smooth)");
        warn("material " + name + ": transparent is written as pbrt's thindielectric (exact Fresnel with inter-reflections where Glint uses Schlick's; renders differ)");
        break;
      case MaterialType::refractive:
        text += "\"dielectric\" \"float eta\" [ " + float_text(m.ior) + " ]" + roughness(m);
        if (!is_white(m.color) || !m.color_texture.empty()) warn("material " + name + ": the tint of solid glass is not written (pbrt's dielectric has none)");
        break;
    }
    add(text);
    if (!m.emission_texture.empty())
      warn("material " + name + ": its emission texture is not written (pbrt's diffuse area light takes no texture)");
    if (!m.roughness_texture.empty())
      warn("material " + name + ": its roughness texture is not written (Glint's alpha is (roughness x texture)^2, which pbrt's roughness texture cannot express)");
  }

  const Material& material_of(const std::string& name) const {
    static const Material fallback;
    const int i = find_material(scene_, name);
    return i >= 0 ? scene_.materials[i] : fallback;
  }

  // The opening of a shape's block: its name as a comment (pbrt's shapes have none; the reader
  // takes it back), material, emission and coverage.
  std::string begin(const std::string& kind, const std::string& name, const Material& m) {
    add("AttributeBegin  # " + kind + " " + quoted(name));
    add("  NamedMaterial " + quoted(m.name));
    if (m.emission != glm::vec3(0.0f))
      add("  AreaLightSource \"diffuse\" \"rgb L\" [ " + vec(m.emission) + " ] \"bool twosided\" true");
    return m.opacity < 1 ? " \"float alpha\" [ " + float_text(m.opacity) + " ]" : "";
  }

  void sphere(const Sphere& s) {
    const Material& m = material_of(s.material);
    const std::string alpha = begin("sphere", s.name, m);
    add("  Translate " + vec(s.center));
    if (!m.color_texture.empty()) {
      add("  ConcatTransform [ 1 0 0 0  0 0 1 0  0 1 0 0  0 0 0 1 ]  # object +Z along world +Y: Glint's sphere uvs");
      add("  ReverseOrientation");
    }
    add("  Shape \"sphere\" \"float radius\" [ " + float_text(s.radius) + " ]" + alpha);
    add("AttributeEnd");
  }

  void quad(const Quad& q) {
    const std::string alpha = begin("quad", q.name, material_of(q.material));
    std::string points, uvs;
    for (int k = 0; k < 4; ++k) {
      points += (k ? "  " : "") + vec(q.corners[k]);
      uvs += (k ? "  " : "") + float_text(q.uvs[k].x) + " " + num(1.0 - double(q.uvs[k].y));
    }
    const bool patch = quad_is_parallelogram(q.corners) && affine_uvs(q);
    if (patch)
      add("  Shape \"bilinearmesh\" \"point3 P\" [ " + points + " ] \"point2 uv\" [ " + uvs + " ]" + alpha);
    else
      add("  Shape \"trianglemesh\" \"point3 P\" [ " + points + " ] \"integer indices\" [ 0 1 2 1 3 2 ] \"point2 uv\" [ " + uvs + " ]" + alpha);
    add("AttributeEnd");
  }

  const Scene& scene_;
  ExportOptions options_;
  ExportedScene out_;
};

}  // namespace

ExportedScene write_pbrt_scene(const Scene& scene, const std::string& stem, const ExportOptions& options) {
  return PbrtWriter(scene, options).write();
}

}  // namespace glint
