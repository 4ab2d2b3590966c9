#include "renderer/gl_program.h"

#include <stdexcept>
#include <vector>

#include "renderer/shader_sources.h"

namespace glint {
namespace {

// GL_COMPLETION_STATUS_KHR (== _ARB); spelled out in case the headers lack it.
constexpr GLenum kCompletionStatus = 0x91B1;

GLuint issue_compile(GLenum stage, const std::string& name, const std::string& defines) {
  std::string text = shader_source(name, defines);
  const char* src = text.c_str();
  GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &src, nullptr);
  glCompileShader(shader);
  return shader;
}

std::string shader_log(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<size_t>(length) + 1);
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  return log.data();
}

}  // namespace

bool has_parallel_shader_compile() {
  return epoxy_has_gl_extension("GL_KHR_parallel_shader_compile") ||
         epoxy_has_gl_extension("GL_ARB_parallel_shader_compile");
}

GlProgram::GlProgram(Deferred, const std::vector<Stage>& stages, const std::string& defines) {
  id_ = glCreateProgram();
  for (size_t i = 0; i < stages.size() && i < 2; ++i) {
    names_[i] = stages[i].name;
    shaders_[i] = issue_compile(stages[i].type, stages[i].name, i + 1 == stages.size() ? defines : "");
    glAttachShader(id_, shaders_[i]);
  }
  glLinkProgram(id_);
}

GlProgram::GlProgram(const std::string& vertex_name, const std::string& fragment_name,
                     const std::string& defines)
    : GlProgram(Deferred{}, {{GL_VERTEX_SHADER, vertex_name}, {GL_FRAGMENT_SHADER, fragment_name}},
                defines) {
  finish();
}

std::unique_ptr<GlProgram> GlProgram::start(const std::string& vertex_name,
                                            const std::string& fragment_name,
                                            const std::string& defines) {
  return std::unique_ptr<GlProgram>(new GlProgram(
      Deferred{}, {{GL_VERTEX_SHADER, vertex_name}, {GL_FRAGMENT_SHADER, fragment_name}}, defines));
}

std::unique_ptr<GlProgram> GlProgram::start_compute(const std::string& compute_name,
                                                    const std::string& defines) {
  return std::unique_ptr<GlProgram>(
      new GlProgram(Deferred{}, {{GL_COMPUTE_SHADER, compute_name}}, defines));
}

std::unique_ptr<GlProgram> GlProgram::compute(const std::string& compute_name,
                                              const std::string& defines) {
  auto program = start_compute(compute_name, defines);
  program->finish();
  return program;
}

bool GlProgram::ready() const {
  if (finished_ || !has_parallel_shader_compile()) return true;
  GLint done = GL_FALSE;
  glGetProgramiv(id_, kCompletionStatus, &done);
  return done == GL_TRUE;
}

void GlProgram::finish() {
  if (finished_) return;
  std::string error;
  for (int i = 0; i < 2 && error.empty(); ++i) {
    if (!shaders_[i]) continue;
    GLint ok = 0;
    glGetShaderiv(shaders_[i], GL_COMPILE_STATUS, &ok);
    if (!ok) error = "shaders/" + names_[i] + " failed to compile:\n" + shader_log(shaders_[i]);
  }
  if (error.empty()) {
    GLint ok = 0;
    glGetProgramiv(id_, GL_LINK_STATUS, &ok);
    if (!ok) {
      GLint length = 0;
      glGetProgramiv(id_, GL_INFO_LOG_LENGTH, &length);
      std::vector<char> log(static_cast<size_t>(length) + 1);
      glGetProgramInfoLog(id_, length, nullptr, log.data());
      error = (names_[1].empty() ? names_[0] : names_[0] + " + " + names_[1]) + " failed to link:\n" + log.data();
    }
  }
  for (GLuint& s : shaders_) {
    if (!s) continue;
    glDetachShader(id_, s);
    glDeleteShader(s);
    s = 0;
  }
  if (!error.empty()) {
    glDeleteProgram(id_);
    id_ = 0;
    throw std::runtime_error(error);
  }
  finished_ = true;
}

GlProgram::~GlProgram() {
  for (GLuint s : shaders_)
    if (s) glDeleteShader(s);
  if (id_) glDeleteProgram(id_);
}

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

void GlProgram::set(const char* name, glm::ivec4 v) {
  glProgramUniform4i(id_, location(name), v.x, v.y, v.z, v.w);
}

}  // namespace glint
