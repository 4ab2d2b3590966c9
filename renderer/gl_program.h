// A linked GLSL program from embedded shader files, with cached uniform look-ups.
#pragma once

#include <string>
#include <unordered_map>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

namespace glint {

class GlProgram {
 public:
  // Compiles and links; throws std::runtime_error with the driver's log on failure.
  GlProgram(const std::string& vertex_name, const std::string& fragment_name);
  ~GlProgram();
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  GLuint id() const { return id_; }
  void set(const char* name, int v);
  void set(const char* name, unsigned v);
  void set(const char* name, float v);
  void set(const char* name, glm::vec3 v);
  void set(const char* name, glm::ivec2 v);

 private:
  GLint location(const char* name);
  GLuint id_ = 0;
  std::unordered_map<std::string, GLint> locations_;
};

}  // namespace glint
