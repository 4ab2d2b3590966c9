#include "renderer/mitsuba_values.h"

#include <cmath>
#include <cstdlib>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/json_fields.h"
#include "renderer/project_error.h"

namespace glint::mitsuba {

std::string Context::where(const XmlElement& e) const {
  std::string tag = "<" + e.name;
  for (const char* key : {"type", "name", "id"})
    if (const std::string* v = e.attribute(key)) tag += std::string(" ") + key + "=\"" + json_fields::clip(*v, 60) + "\"";
  return "line " + std::to_string(e.line) + ": " + tag + ">";
}

void Context::fail(const XmlElement& e, const std::string& problem) const { throw ProjectError(file, where(e), problem); }

void Context::warn(const XmlElement& e, const std::string& text) { warnings.push_back(file + ": " + where(e) + ": " + text); }

void Context::warn_counts(const std::string& prefix, const std::map<std::string, size_t>& counts) {
  if (counts.empty()) return;
  std::string text;
  for (const auto& [what, n] : counts) text += (text.empty() ? "" : ", ") + std::to_string(n) + " " + what;
  warnings.push_back(file + ": " + prefix + text);
}

std::string Context::substitute(const XmlElement& e, const std::string& text) const {
  std::string out;
  for (size_t i = 0; i < text.size();) {
    if (text[i] != '$') {
      out += text[i++];
      continue;
    }
    size_t end = i + 1;
    while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '_')) ++end;
    const std::string name = text.substr(i + 1, end - i - 1);
    const auto found = defaults.find(name);
    if (found == defaults.end()) fail(e, "parameter $" + json_fields::clip(name, 40) + " has no <default>");
    out += found->second;
    i = end;
  }
  return out;
}

std::string Context::required(const XmlElement& e, const std::string& attribute) const {
  const std::string* v = e.attribute(attribute);
  if (!v) fail(e, "needs a " + attribute + " attribute");
  return substitute(e, *v);
}

std::vector<double> numbers(const Context& ctx, const XmlElement& e, const std::string& text, size_t min, size_t max) {
  std::vector<double> out;
  const char* p = text.c_str();
  for (;;) {
    while (*p == ' ' || *p == ',' || *p == '\t' || *p == '\n' || *p == '\r') ++p;
    if (!*p) break;
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p || !std::isfinite(v) || (*end && *end != ' ' && *end != ',' && *end != '\t' && *end != '\n' && *end != '\r'))
      ctx.fail(e, "expected a number, got '" + json_fields::clip(text, 40) + "'");
    out.push_back(v);
    p = end;
  }
  if (out.size() < min || out.size() > max)
    ctx.fail(e, "expected " + (min == max ? std::to_string(min) : std::to_string(min) + " to " + std::to_string(max)) +
                    " numbers, got " + std::to_string(out.size()));
  return out;
}

// ---- Props ----

const XmlElement* Props::child(const std::string& tag) {
  for (size_t i = 0; i < e_.children.size(); ++i)
    if (!used_[i] && e_.children[i].name == tag) return used_[i] = true, &e_.children[i];
  return nullptr;
}

const XmlElement* Props::find(const std::string& name) {
  for (size_t i = 0; i < e_.children.size(); ++i) {
    const std::string* n = e_.children[i].attribute("name");
    if (n && *n == name) return used_[i] = true, &e_.children[i];
  }
  return nullptr;
}

double Props::number(const std::string& name, double fallback) {
  const XmlElement* c = find(name);
  if (!c) return fallback;
  if (c->name != "float" && c->name != "integer") ctx_.fail(*c, "expected <float name=\"" + name + "\">");
  return numbers(ctx_, *c, ctx_.required(*c, "value"), 1, 1)[0];
}

long Props::integer(const std::string& name, long fallback) {
  const XmlElement* c = find(name);
  if (!c) return fallback;
  if (c->name != "integer") ctx_.fail(*c, "expected <integer name=\"" + name + "\">");
  const double v = numbers(ctx_, *c, ctx_.required(*c, "value"), 1, 1)[0];
  if (v != std::floor(v) || std::abs(v) > 2147483647.0) ctx_.fail(*c, "expected an integer");
  return long(v);
}

bool Props::boolean(const std::string& name, bool fallback) {
  const XmlElement* c = find(name);
  if (!c) return fallback;
  const std::string v = ctx_.required(*c, "value");
  if (c->name != "boolean" || (v != "true" && v != "false")) ctx_.fail(*c, "expected <boolean name=\"" + name + "\" value=\"true\" or \"false\">");
  return v == "true";
}

std::string Props::string(const std::string& name, const std::string& fallback) {
  const XmlElement* c = find(name);
  if (!c) return fallback;
  if (c->name != "string") ctx_.fail(*c, "expected <string name=\"" + name + "\">");
  return ctx_.required(*c, "value");
}

glm::vec3 Props::attribute_vec3(const std::string& attribute, std::optional<glm::vec3> fallback) {
  if (!e_.attribute(attribute) && fallback) return *fallback;
  const std::vector<double> v = numbers(ctx_, e_, ctx_.required(e_, attribute), 3, 3);
  return glm::vec3(v[0], v[1], v[2]);
}

glm::vec3 Props::vec3(const std::string& name, glm::vec3 fallback) {
  const XmlElement* c = find(name);
  if (!c) return fallback;
  if (c->name != "point" && c->name != "vector") ctx_.fail(*c, "expected <point name=\"" + name + "\">");
  if (c->attribute("value")) return Props(ctx_, *c).attribute_vec3("value");
  glm::vec3 out(0);
  const char* keys[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k)
    if (c->attribute(keys[k])) out[k] = float(numbers(ctx_, *c, ctx_.required(*c, keys[k]), 1, 1)[0]);
  return out;
}

glm::vec3 Props::colour(const std::string& name, glm::vec3 fallback) {
  const XmlElement* c = find(name);
  if (!c) return fallback;
  if (c->name != "rgb" && c->name != "float" && c->name != "spectrum")
    ctx_.fail(*c, "expected <rgb name=\"" + name + "\">");
  const std::vector<double> v = numbers(ctx_, *c, ctx_.required(*c, "value"), 1, c->name == "rgb" ? 3 : 1);
  if (v.size() == 2) ctx_.fail(*c, "expected 1 or 3 numbers, got 2");
  if (c->name == "spectrum") ctx_.warn(*c, "read as a grey of its value (Glint's colours are RGB)");
  return v.size() == 3 ? glm::vec3(v[0], v[1], v[2]) : glm::vec3(float(v[0]));
}

const XmlElement* Props::transform(const std::string& name) {
  const XmlElement* c = find(name);
  if (c && c->name != "transform") ctx_.fail(*c, "expected <transform name=\"" + name + "\">");
  return c;
}

void Props::skip(std::initializer_list<const char*> names) {
  for (const char* n : names) find(n);
}

void Props::skip_all() { used_.assign(used_.size(), true); }

void Props::finish() {
  for (size_t i = 0; i < e_.children.size(); ++i)
    if (!used_[i]) ctx_.warn(e_.children[i], std::string("not imported (") + (e_.children[i].attribute("name") ? "Glint has no such setting" : "unexpected here") + ")");
}

// ---- Transforms ----

glm::dmat4 transform(Context& ctx, const XmlElement& t) {
  glm::dmat4 m(1.0);
  for (const XmlElement& c : t.children) {
    Props p(ctx, c);
    auto xyz = [&](double fallback) {
      if (c.attribute("value")) {
        const std::vector<double> v = numbers(ctx, c, ctx.required(c, "value"), 1, 3);
        return v.size() == 1 ? glm::dvec3(v[0]) : v.size() == 3 ? glm::dvec3(v[0], v[1], v[2]) : (ctx.fail(c, "expected 1 or 3 numbers"), glm::dvec3());
      }
      glm::dvec3 out(fallback);
      const char* keys[3] = {"x", "y", "z"};
      for (int k = 0; k < 3; ++k)
        if (c.attribute(keys[k])) out[k] = numbers(ctx, c, ctx.required(c, keys[k]), 1, 1)[0];
      return out;
    };
    glm::dmat4 step(1.0);
    if (c.name == "translate") {
      step = glm::translate(glm::dmat4(1.0), xyz(0));
    } else if (c.name == "scale") {
      step = glm::scale(glm::dmat4(1.0), xyz(1));
    } else if (c.name == "rotate") {
      const glm::dvec3 axis = xyz(0);
      const double angle = numbers(ctx, c, ctx.required(c, "angle"), 1, 1)[0];
      if (glm::length(axis) == 0) ctx.fail(c, "the rotation axis is zero");
      step = glm::rotate(glm::dmat4(1.0), glm::radians(angle), glm::normalize(axis));
    } else if (c.name == "matrix") {
      const std::vector<double> v = numbers(ctx, c, ctx.required(c, "value"), 9, 16);
      if (v.size() != 9 && v.size() != 16) ctx.fail(c, "a matrix has 9 or 16 numbers");
      const size_t n = v.size() == 9 ? 3 : 4;
      for (size_t r = 0; r < n; ++r)
        for (size_t col = 0; col < n; ++col) step[col][r] = v[r * n + col];  // rows in the file
    } else if (c.name == "lookat") {
      const glm::dvec3 origin(p.attribute_vec3("origin")), target(p.attribute_vec3("target"));
      const glm::dvec3 up(p.attribute_vec3("up", glm::vec3(0, 1, 0)));
      const glm::dvec3 dir = glm::normalize(target - origin);
      const glm::dvec3 left = glm::normalize(glm::cross(up, dir));
      const glm::dvec3 new_up = glm::cross(dir, left);
      step = glm::dmat4(glm::dvec4(left, 0), glm::dvec4(new_up, 0), glm::dvec4(dir, 0), glm::dvec4(origin, 1));
    } else {
      ctx.fail(c, "unknown transform (translate, rotate, scale, matrix or lookat)");
    }
    m = step * m;
  }
  return m;
}

double y_rotation_deg(Context& ctx, const XmlElement& t) {
  if (t.children.size() == 1 && t.children[0].name == "rotate") {
    const XmlElement& r = t.children[0];
    const std::string* x = r.attribute("x");
    const std::string* y = r.attribute("y");
    const std::string* z = r.attribute("z");
    const bool zero_x = !x || numbers(ctx, r, ctx.substitute(r, *x), 1, 1)[0] == 0;
    const bool zero_z = !z || numbers(ctx, r, ctx.substitute(r, *z), 1, 1)[0] == 0;
    if (zero_x && zero_z && y && !r.attribute("value") && numbers(ctx, r, ctx.substitute(r, *y), 1, 1)[0] > 0)
      return numbers(ctx, r, ctx.required(r, "angle"), 1, 1)[0];
  }
  const glm::dmat4 m = transform(ctx, t);
  const glm::dvec3 x(m[0]), y(m[1]);
  if (std::abs(y.x) > 1e-6 || std::abs(y.y - 1) > 1e-6 || std::abs(y.z) > 1e-6 || std::abs(x.y) > 1e-6)
    ctx.warn(t, "only the turn about +Y is imported (Glint rotates its environment about +Y)");
  return glm::degrees(std::atan2(-x.z, x.x));
}

double vertical_fov(double fov, const std::string& axis, int width, int height, Context& ctx, const XmlElement& e) {
  if (axis == "y") return fov;
  const double t = std::tan(glm::radians(fov) / 2), w = width, h = height;
  double ratio = 1;  // tan(vfov / 2) / tan(fov / 2)
  if (axis == "x" || (axis == "smaller" && w < h) || (axis == "larger" && w > h)) ratio = h / w;
  else if (axis == "diagonal") ratio = h / std::sqrt(w * w + h * h);
  else if (axis != "y" && axis != "smaller" && axis != "larger") ctx.fail(e, "unknown fov_axis '" + json_fields::clip(axis, 20) + "'");
  return glm::degrees(2 * std::atan(t * ratio));
}

}  // namespace glint::mitsuba
