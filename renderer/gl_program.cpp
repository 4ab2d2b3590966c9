#include "renderer/gl_program.h"

#include <stdexcept>
#include <vector>

#include "renderer/shader_sources.h"

namespace glint {
namespace {

GLuint compile(GLenum stage, const std::string& name) {
  std::string text = shader_source(name);
  const char* src = text.c_str();
  GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &src, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<size_t>(length) + 1);
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    glDeleteShader(shader);
    throw std::runtime_error("shaders/" + name + " failed to compile:\n" + log.data());
  }
  return shader;
}

}  // namespace

GlProgram::GlProgram(const std::string& vertex_name, const std::string& fragment_name) {
  GLuint vs = compile(GL_VERTEX_SHADER, vertex_name);
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, fragment_name);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  id_ = glCreateProgram();
  glAttachShader(id_, vs);
  glAttachShader(id_, fs);
  glLinkProgram(id_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(id_, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<size_t>(length) + 1);
    glGetProgramInfoLog(id_, length, nullptr, log.data());
    glDeleteProgram(id_);
    throw std::runtime_error(vertex_name + " + " + fragment_name + " failed to link:\n" + log.data());
  }
}

GlProgram::~GlProgram() { glDeleteProgram(id_); }

GLint GlProgram::location(const char* name) {
  auto it = locations_.find(name);
  if (it != locations_.end()) return it->second;
  GLint loc = glGetUniformLocation(id_, name);  // -1 (ignored by glProgramUniform) if unused
  locations_.emplace(name, loc);
  return loc;
}

void GlProgram::set(const char* name, int v) { glProgramUniform1i(id_, location(name), v); }
void GlProgram::set(const char* name, unsigned v) { glProgramUniform1ui(id_, location(name), v); }
void GlProgram::set(const char* name, float v) { glProgramUniform1f(id_, location(name), v); }
void GlProgram::set(const char* name, glm::vec3 v) {
  glProgramUniform3f(id_, location(name), v.x, v.y, v.z);
}
void GlProgram::set(const char* name, glm::ivec2 v) {
  glProgramUniform2i(id_, location(name), v.x, v.y);
}

}  // namespace glint
