#include "renderer/pbrt_tokens.h"

#include <cctype>
#include <cmath>
#include <cstdlib>

#include "renderer/json_fields.h"
#include "renderer/project_error.h"

namespace glint::pbrt {

std::vector<Token> tokenize(const std::string& text, const std::string& file) {
  std::vector<Token> tokens;
  int line = 1;
  size_t i = 0;
  auto fail = [&](const std::string& problem) { throw ProjectError(file, "line " + std::to_string(line), problem); };
  if (!json_fields::is_valid_utf8(text)) fail("the file is not UTF-8 text");
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line, ++i;
    } else if (std::isspace(static_cast<unsigned char>(c))) {  // also \v and \f, which end a word
      ++i;
    } else if (c == '\0') {
      fail("the file holds a NUL byte");
    } else if (c == '#') {
      const size_t end = text.find('\n', i);
      const std::string comment = text.substr(i + 1, end == std::string::npos ? std::string::npos : end - i - 1);
      if (!tokens.empty() && tokens.back().line == line) tokens.back().comment = comment;
      i = end == std::string::npos ? text.size() : end;
    } else if (c == '[' || c == ']') {
      tokens.push_back({std::string(1, c), false, line, {}});
      ++i;
    } else if (c == '"') {
      Token t{"", true, line, {}};
      for (++i;; ++i) {
        if (i >= text.size() || text[i] == '\n') fail("a string is not closed by '\"'");
        if (text[i] == '"') break;
        if (text[i] == '\\' && i + 1 < text.size()) {
          const char e = text[++i];
          t.text += e == 'n' ? '\n' : e == 't' ? '\t' : e;
        } else {
          t.text += text[i];
        }
      }
      ++i;
      tokens.push_back(std::move(t));
    } else {
      const size_t start = i;
      while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i])) && text[i] != '[' && text[i] != ']' &&
             text[i] != '"' && text[i] != '#')
        ++i;
      tokens.push_back({text.substr(start, i - start), false, line, {}});
    }
  }
  return tokens;
}

void Params::fail(const Param& p, const std::string& problem) const {
  throw ProjectError(file_, "line " + std::to_string(p.line) + ": " + directive_ + " \"" + p.type + " " + p.name + "\"", problem);
}

const Param* Params::find(const std::string& name) const {
  for (const Param& p : list)
    if (p.name == name) return p.used = true, &p;
  return nullptr;
}

static double to_number(const Params& ps, const Param& p, const Token& t) {
  char* end = nullptr;
  const double v = std::strtod(t.text.c_str(), &end);
  if (t.quoted || t.text.empty() || end != t.text.c_str() + t.text.size() || !std::isfinite(v))
    ps.fail(p, "expected a number, got '" + json_fields::clip(t.text, 40) + "'");
  return v;
}

std::vector<double> Params::numbers(const std::string& name) const {
  const Param* p = find(name);
  std::vector<double> out;
  if (!p) return out;
  if (p->type != "float" && p->type != "integer" && p->type != "point3" && p->type != "point2" && p->type != "rgb" &&
      p->type != "normal" && p->type != "vector3" && p->type != "point" && p->type != "normal3" && p->type != "vector")
    fail(*p, "expected numbers");
  for (const Token& t : p->values) out.push_back(to_number(*this, *p, t));
  return out;
}

double Params::number(const std::string& name, double fallback) const {
  const Param* p = find(name);
  if (!p) return fallback;
  if (p->type == "texture") fail(*p, "a texture here is not supported (Glint takes a number)");
  const std::vector<double> v = numbers(name);
  if (v.size() != 1) fail(*p, "expected one number");
  return v[0];
}

bool Params::boolean(const std::string& name, bool fallback) const {
  const Param* p = find(name);
  if (!p) return fallback;
  if (p->type != "bool" || p->values.size() != 1 || (p->values[0].text != "true" && p->values[0].text != "false"))
    fail(*p, "expected true or false");
  return p->values[0].text == "true";
}

std::string Params::string(const std::string& name, const std::string& fallback) const {
  const Param* p = find(name);
  if (!p) return fallback;
  if ((p->type != "string" && p->type != "texture") || p->values.size() != 1 || !p->values[0].quoted) fail(*p, "expected one string");
  return p->values[0].text;
}

glm::vec3 Params::rgb(const std::string& name, glm::vec3 fallback) const {
  const Param* p = find(name);
  if (!p) return fallback;
  if (p->type == "rgb") {
    const std::vector<double> v = numbers(name);
    if (v.size() != 3) fail(*p, "expected 3 numbers");
    return glm::vec3(v[0], v[1], v[2]);
  }
  if (p->type == "float") return glm::vec3(float(number(name, 0)));
  fail(*p, "expected an rgb colour (Glint's colours are RGB)");
}

std::string Params::texture(const std::string& name) const {
  for (const Param& p : list)
    if (p.name == name && p.type == "texture") return string(name, "");
  return "";
}

std::vector<std::string> Params::unused() const {
  std::vector<std::string> out;
  for (const Param& p : list)
    if (!p.used) out.push_back("\"" + p.type + " " + p.name + "\"");
  return out;
}

}  // namespace glint::pbrt
