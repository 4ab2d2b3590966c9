#include "renderer/shader_sources.h"

#include <set>
#include <sstream>
#include <stdexcept>

namespace glint {
namespace {

void expand(const std::string& name, std::set<std::string>& seen, std::string& out) {
  const auto& table = embedded_shaders();
  auto it = table.find(name);
  if (it == table.end()) throw std::runtime_error("shader file not embedded: shaders/" + name);
  if (!seen.insert(name).second) return;
  std::istringstream in(it->second);
  std::string line;
  while (std::getline(in, line)) {
    const std::string directive = "#include \"";
    if (line.rfind(directive, 0) == 0) {
      auto end = line.find('"', directive.size());
      expand(line.substr(directive.size(), end - directive.size()), seen, out);
    } else {
      out += line;
      out += '\n';
    }
  }
}

}  // namespace

std::string shader_source(const std::string& name) {
  std::set<std::string> seen;
  std::string out;
  expand(name, seen, out);
  return out;
}

std::string shader_source(const std::string& name, const std::string& defines) {
  std::string text = shader_source(name);
  if (defines.empty()) return text;
  if (text.rfind("#version", 0) != 0)
    throw std::runtime_error("shaders/" + name + " does not start with #version");
  size_t eol = text.find('\n');
  return text.insert(eol == std::string::npos ? text.size() : eol + 1, defines);
}

}  // namespace glint
