// pbrt-v4 scene file -> Glint scene: the inverse of pbrt_writer.cpp's conventions, and the
// common subset of other scenes (pbrt's defaults where a parameter is absent). Parameters that
// nothing reads are named in a warning; shapes and lights Glint does not model are counted.
#include <cmath>
#include <map>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "renderer/json_fields.h"
#include "renderer/pbrt_materials.h"
#include "renderer/pbrt_scene.h"
#include "renderer/pbrt_tokens.h"
#include "renderer/quad_shape.h"
#include "renderer/scene_fields.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

using pbrt::Params;
using pbrt::Token;

struct GraphicsState {
  glm::dmat4 ctm{1.0};
  bool reverse_orientation = false;
  std::string material = "";  // a Glint material's name; "" until one is set (pbrt's default diffuse)
  std::optional<glm::vec3> emission;
};

// pbrt's LookAt: camera-from-world.
glm::dmat4 look_at(glm::dvec3 eye, glm::dvec3 look, glm::dvec3 up) {
  const glm::dvec3 dir = glm::normalize(look - eye);
  const glm::dvec3 right = glm::normalize(glm::cross(glm::normalize(up), dir));
  const glm::dvec3 new_up = glm::cross(dir, right);
  return glm::inverse(glm::dmat4(glm::dvec4(right, 0), glm::dvec4(new_up, 0), glm::dvec4(dir, 0), glm::dvec4(eye, 1)));
}

bool near(const glm::dmat4& a, const glm::dmat4& b) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (std::abs(a[c][r] - b[c][r]) > 1e-9 * (1 + std::abs(a[c][r]))) return false;
  return true;
}

class PbrtReader {
 public:
  PbrtReader(const std::string& text, const std::string& file) : tokens_(pbrt::tokenize(text, file)), file_(file) {
    scene_.environment.color = glm::vec3(0);  // no light: a black background
  }

  ImportedScene read() {
    while (pos_ < tokens_.size()) directive();
    if (!world_) throw ProjectError(file_, "", "no WorldBegin: the file describes no scene");
    counts("not imported (Glint models spheres and quads): ", skipped_shapes_);
    counts("not imported (Glint's lights are emissive surfaces and the environment): ", skipped_lights_);
    return {std::move(scene_), std::move(warnings_)};
  }

 private:
  // ---- Tokens ----
  const Token& next(const char* what) {
    if (pos_ >= tokens_.size()) throw ProjectError(file_, "line " + std::to_string(tokens_.empty() ? 1 : tokens_.back().line), std::string("the file ends where ") + what + " was expected");
    return tokens_[pos_++];
  }
  [[noreturn]] void fail(const std::string& problem) const {
    throw ProjectError(file_, "line " + std::to_string(line_) + ": " + directive_, problem);
  }
  void warn(const std::string& text) { warnings_.push_back(file_ + ": line " + std::to_string(line_) + ": " + directive_ + ": " + text); }
  void counts(const std::string& prefix, const std::map<std::string, size_t>& c) {
    if (c.empty()) return;
    std::string text;
    for (const auto& [what, n] : c) text += (text.empty() ? "" : ", ") + std::to_string(n) + " " + what;
    warnings_.push_back(file_ + ": " + prefix + text);
  }
  std::string string_arg() {
    const Token& t = next("a quoted string");
    if (!t.quoted) fail("expected a quoted string, got '" + json_fields::clip(t.text, 40) + "'");
    return t.text;
  }
  double number_arg() {
    const Token& t = next("a number");
    char* end = nullptr;
    const double v = std::strtod(t.text.c_str(), &end);
    if (t.quoted || t.text.empty() || end != t.text.c_str() + t.text.size() || !std::isfinite(v))
      fail("expected a number, got '" + json_fields::clip(t.text, 40) + "'");
    return v;
  }
  glm::dvec3 vec_arg() {
    const double x = number_arg(), y = number_arg(), z = number_arg();
    return {x, y, z};
  }
  glm::dmat4 matrix_arg() {
    const bool bracket = pos_ < tokens_.size() && tokens_[pos_].text == "[" && !tokens_[pos_].quoted;
    if (bracket) ++pos_;
    double v[16];
    for (double& x : v) x = number_arg();
    if (bracket && next("']'").text != "]") fail("expected ']' after 16 numbers");
    return glm::make_mat4(v);  // pbrt lists the matrix column by column, as glm stores it
  }
  Params params() {
    Params ps(file_, directive_, line_);
    while (pos_ < tokens_.size() && tokens_[pos_].quoted && tokens_[pos_].text.find(' ') != std::string::npos) {
      const Token& decl = tokens_[pos_++];
      pbrt::Param p;
      p.line = decl.line;
      const size_t space = decl.text.find(' ');
      const size_t name = decl.text.find_first_not_of(' ', space);
      p.type = decl.text.substr(0, space);
      if (name == std::string::npos || p.type.empty() || decl.text.find(' ', name) != std::string::npos)
        fail("a parameter is \"TYPE NAME\", got \"" + json_fields::clip(decl.text, 40) + "\"");
      p.name = decl.text.substr(name);
      if (pos_ < tokens_.size() && tokens_[pos_].text == "[" && !tokens_[pos_].quoted) {
        for (++pos_;;) {
          const Token& v = next("']'");
          if (v.text == "]" && !v.quoted) break;
          p.values.push_back(v);
        }
      } else {
        p.values.push_back(next("a parameter value"));
      }
      ps.list.push_back(std::move(p));
    }
    return ps;
  }
  void finish(const Params& ps) {
    const std::vector<std::string> unused = ps.unused();
    if (unused.empty()) return;
    std::string text;
    for (const std::string& u : unused) text += (text.empty() ? "" : ", ") + u;
    warn("not imported (Glint has no such setting): " + text);
  }

  // ---- Directives ----
  // The current transformation's directives; false for any other.
  bool transform_directive(const std::string& d) {
    GraphicsState& gs = state_.back();
    if (d == "LookAt") {
      const glm::dvec3 eye = vec_arg(), look = vec_arg(), up = vec_arg();
      before_look_at_ = gs.ctm;
      gs.ctm = gs.ctm * look_at(eye, look, up);
      look_at_ = std::array<glm::dvec3, 3>{eye, look, up};
    } else if (d == "Translate") {
      gs.ctm = gs.ctm * glm::translate(glm::dmat4(1.0), vec_arg());
    } else if (d == "Scale") {
      gs.ctm = gs.ctm * glm::scale(glm::dmat4(1.0), vec_arg());
    } else if (d == "Rotate") {
      const double angle = number_arg();
      const glm::dvec3 axis = vec_arg();
      if (glm::length(axis) == 0) fail("the rotation axis is zero");
      gs.ctm = gs.ctm * glm::rotate(glm::dmat4(1.0), glm::radians(angle), glm::normalize(axis));
    } else if (d == "Transform") {
      gs.ctm = matrix_arg();
    } else if (d == "ConcatTransform") {
      gs.ctm = gs.ctm * matrix_arg();
    } else if (d == "Identity") {
      gs.ctm = glm::dmat4(1.0);
    } else if (d == "CoordinateSystem") {
      coordinate_systems_[string_arg()] = gs.ctm;
    } else if (d == "CoordSysTransform") {
      const std::string name = string_arg();
      const auto found = coordinate_systems_.find(name);
      if (found == coordinate_systems_.end()) fail("no coordinate system \"" + json_fields::clip(name, 40) + "\"");
      gs.ctm = found->second;
    } else if (d == "ReverseOrientation") {
      gs.reverse_orientation = !gs.reverse_orientation;
    } else {
      return false;
    }
    return true;
  }

  // The rendering options before WorldBegin, and WorldBegin; false for any other directive.
  bool option_directive(const std::string& d) {
    if (d == "Camera") {
      const std::string type = string_arg();
      camera(type, params());
    } else if (d == "Film") {
      const std::string type = string_arg();
      film(type, params());
    } else if (d == "Sampler") {
      string_arg();
      const Params ps = params();
      const double spp = ps.number("pixelsamples", 16);
      scene_.render.seed = uint32_t(ps.number("seed", 0));
      warn("its " + json_fields::float_text(float(spp)) + " samples per pixel are not part of a Glint scene (glint render --spp)");
      finish(ps);
    } else if (d == "Integrator") {
      const std::string type = string_arg();
      integrator(type, params());
    } else if (d == "PixelFilter") {
      const std::string type = string_arg();
      const Params ps = params();
      filter_set_ = true;
      if (type != "box" || ps.number("xradius", 0.5) != 0.5 || ps.number("yradius", 0.5) != 0.5)
        warn("Glint filters with a box of one pixel");
      finish(ps);
    } else if (d == "WorldBegin") {
      world_begin();
    } else {
      return false;
    }
    return true;
  }

  void directive() {
    const Token& t = next("a directive");
    line_ = t.line;
    directive_ = t.text;
    if (t.quoted) fail("expected a directive, got a string");
    const std::string& d = t.text;
    GraphicsState& gs = state_.back();
    if (transform_directive(d) || option_directive(d)) return;
    if (d == "AttributeBegin" || d == "TransformBegin") {
      state_.push_back(gs);
      pending_name_ = t.comment;
    } else if (d == "AttributeEnd" || d == "TransformEnd") {
      if (state_.size() == 1) fail("no AttributeBegin to end");
      const GraphicsState top = state_.back();
      state_.pop_back();
      if (d == "TransformEnd") state_.back() = GraphicsState{top.ctm, state_.back().reverse_orientation, state_.back().material, state_.back().emission};
      pending_name_.clear();
    } else if (d == "LightSource") {
      const std::string type = string_arg();
      light(type, params());
    } else if (d == "AreaLightSource") {
      const std::string type = string_arg();
      area_light(type, params());
    } else if (d == "Material") {
      const std::string type = string_arg();
      const Params ps = params();
      gs.material = materials_.read("material", type, ps);
      finish(ps);
    } else if (d == "MakeNamedMaterial") {
      const std::string name = string_arg();
      const Params ps = params();
      named_materials_[name] = materials_.read(name, ps.string("type", ""), ps);
      finish(ps);
    } else if (d == "NamedMaterial") {
      const std::string name = string_arg();
      const auto found = named_materials_.find(name);
      if (found == named_materials_.end()) fail("no MakeNamedMaterial \"" + json_fields::clip(name, 40) + "\" precedes it");
      gs.material = found->second;
    } else if (d == "Texture") {
      texture();
    } else if (d == "Shape") {
      const std::string type = string_arg();
      shape(type, params());
    } else if (d == "ObjectBegin") {
      string_arg();
      ++in_object_;
      state_.push_back(gs);
    } else if (d == "ObjectEnd") {
      if (in_object_ == 0 || state_.size() == 1) fail("no ObjectBegin to end");
      --in_object_;
      state_.pop_back();
    } else if (d == "ObjectInstance") {
      string_arg();
      ++skipped_shapes_["object instance"];
    } else if (d == "Attribute") {
      string_arg();
      finish(params());
    } else if (d == "ColorSpace" || d == "MakeNamedMedium" || d == "Accelerator") {
      const bool named = d != "Accelerator" ;
      string_arg();
      const Params ps = params();
      for (const auto& p : ps.list) p.used = true;
      if (named) warn("not imported (Glint renders in linear sRGB without media)");
    } else if (d == "MediumInterface") {
      string_arg();
      if (pos_ < tokens_.size() && tokens_[pos_].quoted) ++pos_;
      warn("not imported (Glint has no participating media)");
    } else if (d == "Option") {
      finish(params());
    } else if (d == "Include" || d == "Import") {
      fail("not supported: merge the included file into this one");
    } else if (d == "ActiveTransform" || d == "TransformTimes") {
      fail("animated transforms are not supported");
    } else {
      fail("unknown directive");
    }
  }

  void camera(const std::string& type, const Params& ps) {
    if (type != "perspective") warn("read as a perspective camera");
    const glm::dmat4& ctm = state_.back().ctm;
    coordinate_systems_["camera"] = ctm;
    Camera& c = scene_.camera;
    fov_ = ps.number("fov", 90);
    c.aperture_radius = float(ps.number("lensradius", 0));
    c.focus_distance = float(ps.number("focaldistance", 1e6));
    // pbrt's camera space is left-handed: a camera-from-world with a mirror (Scale -1 1 1 before
    // LookAt) sees what Glint's right-handed camera sees.
    const bool mirrored = glm::determinant(glm::dmat3(ctm)) > 0;
    if (mirrored) warn("pbrt's image of this camera (no Scale -1 1 1 before LookAt) is Glint's mirrored left to right");
    if (look_at_ && (near(ctm, glm::scale(glm::dmat4(1.0), glm::dvec3(-1, 1, 1)) * look_at(look_at_->at(0), look_at_->at(1), look_at_->at(2))) ||
                     near(ctm, look_at(look_at_->at(0), look_at_->at(1), look_at_->at(2))))) {
      c.position = glm::vec3(look_at_->at(0));
      c.target = glm::vec3(look_at_->at(1));
      c.up = glm::vec3(look_at_->at(2));
    } else {
      const glm::dmat4 world = glm::inverse(ctm);
      c.position = glm::vec3(world[3]);
      c.target = glm::vec3(glm::dvec3(world[3]) + glm::normalize(glm::dvec3(world[2])));
      c.up = glm::vec3(glm::normalize(glm::dvec3(world[1])));
    }
    if (c.aperture_radius == 0) c.focus_distance = glm::length(c.target - c.position);
    finish(ps);
  }

  void film(const std::string& type, const Params& ps) {
    if (type != "rgb" && type != "gbuffer" && type != "spectral") warn("read as Glint's film (linear RGB)");
    // Checked before the conversion: a double outside int's range is undefined behaviour.
    const double w = ps.number("xresolution", 1280), h = ps.number("yresolution", 720);
    if (!(w >= 1 && w <= 1e6 && h >= 1 && h <= 1e6)) fail("film resolution must be between 1 and 10^6 pixels");
    scene_.film.width = int(w);
    scene_.film.height = int(h);
    ps.find("filename");
    ps.find("savefp16");
    finish(ps);
  }

  void integrator(const std::string& type, const Params& ps) {
    if (type != "path" && type != "volpath") warn("read as Glint's path tracer");
    const double depth = ps.number("maxdepth", 5);
    if (depth < 0 || depth > kMaxBounces) {
      warn("maxdepth " + json_fields::float_text(float(depth)) + " is read as " + std::to_string(kMaxBounces));
      scene_.render.max_bounces = kMaxBounces;
    } else {
      scene_.render.max_bounces = int(depth);
    }
    ps.find("lightsampler");
    finish(ps);
  }

  void world_begin() {
    if (world_) fail("a second WorldBegin");
    world_ = true;
    const Film& f = scene_.film;
    if (f.width < 1 || f.height < 1) fail("the film's resolution must be positive");
    scene_.camera.vfov_deg = float(f.height > f.width ? glm::degrees(2 * std::atan(std::tan(glm::radians(fov_) / 2) * f.height / f.width)) : fov_);
    if (!filter_set_) warn("pbrt's default filter (gaussian) is read as Glint's box of one pixel");
    state_.back().ctm = glm::dmat4(1.0);
    coordinate_systems_["world"] = glm::dmat4(1.0);
  }

  void light(const std::string& type, const Params& ps) {
    if (type != "infinite") {
      ++skipped_lights_["LightSource \"" + type + "\""];
      for (const auto& p : ps.list) p.used = true;
      return;
    }
    Environment& env = scene_.environment;
    env = Environment{};
    env.color = ps.rgb("L", glm::vec3(1)) * float(ps.number("scale", 1));
    const std::string image = ps.string("filename", "");
    if (!image.empty()) warn("its equal-area image " + json_fields::quote_name(image) + " is not imported (Glint's environment image is lat-long): read as its scale");
    finish(ps);
  }

  void area_light(const std::string& type, const Params& ps) {
    if (type != "diffuse") fail("unknown area light (pbrt-v4 has \"diffuse\")");
    glm::vec3 l = ps.rgb("L", glm::vec3(1)) * float(ps.number("scale", 1));
    if (!ps.boolean("twosided", false)) warn("a one-sided area light is read as Glint's, which emits from both sides");
    state_.back().emission = l;
    finish(ps);
  }

  void texture() {
    const std::string name = string_arg();
    const std::string kind = string_arg();
    const std::string cls = string_arg();
    const Params ps = params();
    if (cls != "imagemap") {
      warn("not imported (Glint's textures are images)");
      for (const auto& p : ps.list) p.used = true;
      return;
    }
    const std::string path = ps.string("filename", "");
    if (path.empty()) fail("an imagemap needs a filename");
    if (ps.number("scale", 1) != 1 || ps.boolean("invert", false)) warn("its scale and invert are not imported");
    if (ps.string("wrap", "repeat") != "repeat") warn("Glint's textures repeat");
    ps.find("filter");
    ps.find("encoding");
    finish(ps);
    textures_[name] = path;
  }

  // The Glint material of a shape: the current one with the current area light's emission and
  // the shape's alpha (Glint keeps both in the material). The first shape to use a material
  // gives it its emission and coverage; a shape that differs gets a copy ("NAME-2").
  std::string shape_material(float opacity) {
    const GraphicsState& gs = state_.back();
    std::string base = gs.material;
    if (base.empty()) {
      if (find_material(scene_, "default") < 0) scene_.materials.push_back(Material{"default", MaterialType::matte, glm::vec3(0.5f)});
      base = "default";
    }
    const glm::vec3 emission = gs.emission.value_or(glm::vec3(0));
    const std::string key = base + "|" + json_fields::float_text(emission.x) + "," + json_fields::float_text(emission.y) + "," +
                            json_fields::float_text(emission.z) + "|" + json_fields::float_text(opacity);
    if (const auto found = variants_.find(key); found != variants_.end()) return found->second;
    Material& m = scene_.materials[find_material(scene_, base)];
    if (!claimed_[base]) {
      claimed_[base] = true;
      m.emission = emission;
      m.opacity = opacity;
      return variants_[key] = base;
    }
    Material copy = m;
    copy.emission = emission;
    copy.opacity = opacity;
    for (int n = 2;; ++n)
      if (find_material(scene_, copy.name = base + "-" + std::to_string(n)) < 0) break;
    scene_.materials.push_back(copy);
    return variants_[key] = copy.name;
  }

  // The name the writer leaves in a comment: AttributeBegin  # sphere "NAME"
  std::string shape_name(const char* kind) const {
    const std::string prefix = std::string(" ") + kind + " \"";
    if (pending_name_.rfind(prefix, 0) != 0 || pending_name_.size() < prefix.size() + 1 || pending_name_.back() != '"') return "";
    std::string name;
    for (size_t i = prefix.size(); i + 1 < pending_name_.size(); ++i) {
      if (pending_name_[i] == '\\' && i + 2 < pending_name_.size()) ++i;
      name += pending_name_[i];
    }
    return name;
  }

  void shape(const std::string& type, const Params& ps) {
    if (in_object_ > 0) {
      ++skipped_shapes_["shape inside ObjectBegin (instancing)"];
      for (const auto& p : ps.list) p.used = true;
      return;
    }
    const GraphicsState& gs = state_.back();
    const bool flipped = gs.reverse_orientation != (glm::determinant(glm::dmat3(gs.ctm)) < 0);
    const float opacity = float(ps.number("alpha", 1));
    if (type == "sphere") {
      if (ps.number("zmin", -1e30) > -1e30 || ps.number("zmax", 1e30) < 1e30 || ps.number("phimax", 360) != 360) {
        ++skipped_shapes_["partial sphere"];
        return;
      }
      const glm::dmat4& m = gs.ctm;
      const double sx = glm::length(glm::dvec3(m[0])), sy = glm::length(glm::dvec3(m[1])), sz = glm::length(glm::dvec3(m[2]));
      if (std::abs(sx - sy) > 1e-5 * sx || std::abs(sx - sz) > 1e-5 * sx) {
        ++skipped_shapes_["ellipsoid (a sphere with a non-uniform scale)"];
        return;
      }
      Sphere s{shape_name("sphere"), glm::vec3(m[3]), float(ps.number("radius", 1) * sx), shape_material(opacity)};
      if (flipped && scene_.materials[find_material(scene_, s.material)].type == MaterialType::refractive)
        warn("an inside-out glass sphere is read with its inside the ball");
      scene_.spheres.push_back(s);
    } else if (type == "bilinearmesh" || type == "trianglemesh") {
      quad(type, ps, flipped, opacity);
    } else {
      ++skipped_shapes_["Shape \"" + type + "\""];
      for (const auto& p : ps.list) p.used = true;
      return;
    }
    finish(ps);
  }

  void quad(const std::string& type, const Params& ps, bool flipped, float opacity) {
    const std::vector<double> p = ps.numbers("P");
    const std::vector<double> uv = ps.numbers("uv");
    const std::vector<double> idx = ps.numbers("indices");
    ps.find("N"), ps.find("S");
    const size_t n = p.size() / 3;
    if (p.size() % 3 != 0 || (!uv.empty() && uv.size() != 2 * n)) fail("P needs 3 numbers a vertex, uv 2");
    std::vector<glm::vec3> positions;
    std::vector<glm::vec2> uvs;
    for (size_t i = 0; i < n; ++i) positions.push_back(glm::vec3(state_.back().ctm * glm::dvec4(p[3 * i], p[3 * i + 1], p[3 * i + 2], 1)));
    for (size_t i = 0; i < uv.size() / 2; ++i) uvs.push_back(glm::vec2(float(uv[2 * i]), float(1.0 - uv[2 * i + 1])));
    std::optional<Quad> q;
    if (type == "bilinearmesh" && n == 4 && (idx.empty() || idx == std::vector<double>{0, 1, 2, 3})) {
      q = Quad{};
      for (int k = 0; k < 4; ++k) q->corners[k] = positions[k];
      q->uvs = uvs.empty() ? std::array<glm::vec2, 4>{glm::vec2(0, 1), glm::vec2(1, 1), glm::vec2(0, 0), glm::vec2(1, 0)}
                           : std::array<glm::vec2, 4>{uvs[0], uvs[1], uvs[2], uvs[3]};
      if (!quad_is_planar_convex(q->corners)) warn("a bilinear patch that is not flat is read as two triangles");
    } else if (type == "trianglemesh") {
      std::vector<int> indices;
      for (double i : idx) indices.push_back(i >= 0 && i < 4 ? int(i) : -1);
      if (idx.empty() && n == 3) indices = {0, 1, 2};
      q = exchange::quad_from_triangles(positions, uvs, indices);
    }
    if (!q) {
      const size_t faces = type == "bilinearmesh" ? (idx.empty() ? n / 4 : idx.size() / 4) : (idx.empty() ? n / 3 : idx.size() / 3);
      ++skipped_shapes_[type + " of " + exchange::count_text(faces, type == "bilinearmesh" ? "patch" : "triangle") + " (not a quad)"];
      return;
    }
    if (flipped) {
      std::swap(q->corners[1], q->corners[2]);
      std::swap(q->uvs[1], q->uvs[2]);
    }
    q->name = shape_name("quad");
    q->material = shape_material(opacity);
    scene_.quads.push_back(*q);
  }

  std::vector<Token> tokens_;
  std::string file_;
  size_t pos_ = 0;
  int line_ = 1;
  std::string directive_;
  Scene scene_;
  std::vector<std::string> warnings_;
  std::vector<GraphicsState> state_{GraphicsState{}};
  std::map<std::string, glm::dmat4> coordinate_systems_;
  std::map<std::string, std::string> named_materials_, textures_, variants_;
  pbrt::MaterialReader materials_{scene_, textures_, [this](const std::string& w) { warn(w); }};
  std::map<std::string, bool> claimed_;
  std::map<std::string, size_t> skipped_shapes_, skipped_lights_;
  std::optional<std::array<glm::dvec3, 3>> look_at_;
  glm::dmat4 before_look_at_{1.0};
  std::string pending_name_;
  double fov_ = 90;
  int in_object_ = 0;
  bool world_ = false;
  bool filter_set_ = false;
};

}  // namespace

ImportedScene read_pbrt_scene(const std::string& text, const std::string& file_label, const fs::path& base_dir) {
  return PbrtReader(text, file_label).read();
}

}  // namespace glint
