// pbrt-v4's scene file syntax for pbrt_reader.cpp: tokens (quoted strings, brackets, numbers
// and names, '#' comments) with their lines, and parameter lists ("float radius" [ 1 ]).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace glint::pbrt {

struct Token {
  std::string text;  // a string's contents without quotes
  bool quoted = false;
  int line = 0;
  std::string comment;  // a '#' comment that ends this token's line, for directives
};

// Throws ProjectError(file, "line N", problem) for an unterminated string or a NUL byte.
std::vector<Token> tokenize(const std::string& text, const std::string& file);

struct Param {
  std::string type, name;
  std::vector<Token> values;
  int line = 0;
  mutable bool used = false;
};

class Params {
 public:
  Params(std::string file, std::string directive, int line) : file_(std::move(file)), directive_(std::move(directive)), line_(line) {}
  std::vector<Param> list;

  [[noreturn]] void fail(const Param& p, const std::string& problem) const;
  const Param* find(const std::string& name) const;  // marks it used
  double number(const std::string& name, double fallback) const;
  bool boolean(const std::string& name, bool fallback) const;
  std::string string(const std::string& name, const std::string& fallback) const;
  glm::vec3 rgb(const std::string& name, glm::vec3 fallback) const;  // rgb, or a grey from a float or blackbody-free spectrum
  std::string texture(const std::string& name) const;                // "texture NAME" param, or ""
  std::vector<double> numbers(const std::string& name) const;        // empty when absent
  // "name" of each parameter nothing read, for one warning.
  std::vector<std::string> unused() const;

 private:
  std::string file_, directive_;
  int line_;
};

}  // namespace glint::pbrt
