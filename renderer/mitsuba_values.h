// The values of Mitsuba 3 XML for mitsuba_reader.cpp: properties (<float name=... value=...>
// and its kin) with $parameter substitution, transforms, the field of view and BSDFs, each
// error and warning naming the file, line and element.
#pragma once

#include <functional>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/scene.h"
#include "renderer/xml_reader.h"

namespace glint::mitsuba {

struct Context {
  std::string file;
  std::map<std::string, std::string> defaults;  // <default name value>
  std::vector<std::string> warnings;

  // "line 12: <bsdf type=\"diffuse\" id=\"white\">"
  std::string where(const XmlElement& e) const;
  [[noreturn]] void fail(const XmlElement& e, const std::string& problem) const;
  void warn(const XmlElement& e, const std::string& text);
  // One warning "PREFIX 2 <shape type=\"cube\">, 1 ..." when `counts` is not empty.
  void warn_counts(const std::string& prefix, const std::map<std::string, size_t>& counts);
  // The attribute with $name parameters replaced; ProjectError when it is missing.
  std::string required(const XmlElement& e, const std::string& attribute) const;
  std::string substitute(const XmlElement& e, const std::string& text) const;
};

// The properties of one element. Each look-up marks the child it reads; finish() warns about
// every child nothing read.
class Props {
 public:
  Props(Context& ctx, const XmlElement& e) : ctx_(ctx), e_(e), used_(e.children.size(), false) {}
  const XmlElement& element() const { return e_; }
  std::string type() const { return ctx_.required(e_, "type"); }
  const XmlElement* child(const std::string& tag);  // the first child element of that tag
  const XmlElement* find(const std::string& name);  // the child with that name attribute
  double number(const std::string& name, double fallback);
  long integer(const std::string& name, long fallback);
  bool boolean(const std::string& name, bool fallback);
  std::string string(const std::string& name, const std::string& fallback);
  glm::vec3 vec3(const std::string& name, glm::vec3 fallback);
  glm::vec3 colour(const std::string& name, glm::vec3 fallback);
  const XmlElement* transform(const std::string& name);
  glm::vec3 attribute_vec3(const std::string& attribute, std::optional<glm::vec3> fallback = std::nullopt);
  void skip(std::initializer_list<const char*> names);
  void skip_all();
  void finish();

 private:
  Context& ctx_;
  const XmlElement& e_;
  std::vector<bool> used_;
};

// Numbers of an attribute, separated by commas and/or spaces.
std::vector<double> numbers(const Context& ctx, const XmlElement& e, const std::string& text, size_t min, size_t max);

// A <transform> element's matrix (its children applied in order).
glm::dmat4 transform(Context& ctx, const XmlElement& t);
// The angle of a rotation about +Y (right-handed, degrees); a warning when it is not one.
double y_rotation_deg(Context& ctx, const XmlElement& t);
// The vertical field of view of `fov` degrees along Mitsuba's fov_axis.
double vertical_fov(double fov, const std::string& axis, int width, int height, Context& ctx, const XmlElement& e);

// A Glint material (without name and emission) for a <bsdf>; `texture` turns a <texture> or
// <ref> into a Glint texture name ("" when it is not one).
Material read_bsdf(Context& ctx, const XmlElement& bsdf,
                   const std::function<std::string(const XmlElement&)>& texture);

struct KeyLess {
  bool operator()(const std::pair<std::string, glm::vec3>& a, const std::pair<std::string, glm::vec3>& b) const {
    if (a.first != b.first) return a.first < b.first;
    for (int k = 0; k < 3; ++k)
      if (a.second[k] != b.second[k]) return a.second[k] < b.second[k];
    return false;
  }
};

}  // namespace glint::mitsuba
