// A linked GLSL program from embedded shader files, with cached uniform look-ups: a vertex and
// a fragment shader, or one compute shader.
#pragma once

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

namespace glint {

class GlProgram {
 public:
  // Compiles and links; throws std::runtime_error with the driver's log on failure.
  // `defines` (whole `#define` lines) go after the fragment shader's #version line.
  GlProgram(const std::string& vertex_name, const std::string& fragment_name,
            const std::string& defines = "");
  ~GlProgram();
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  // Issues the compile and link and returns without asking for their result, so that a
  // driver with GL_KHR/ARB_parallel_shader_compile can work in the background. Poll ready(),
  // then call finish() before the first use.
  static std::unique_ptr<GlProgram> start(const std::string& vertex_name,
                                          const std::string& fragment_name,
                                          const std::string& defines = "");
  // The same for a compute program (`defines` after the compute shader's #version line).
  static std::unique_ptr<GlProgram> compute(const std::string& compute_name,
                                            const std::string& defines = "");
  static std::unique_ptr<GlProgram> start_compute(const std::string& compute_name,
                                                  const std::string& defines = "");
  // GL_COMPLETION_STATUS_KHR of the link where the extension exists; true otherwise (a query
  // of the link status would block until the driver is done).
  bool ready() const;
  // Waits for the link if needed and throws std::runtime_error with the log if it failed.
  void finish();

  GLuint id() const { return id_; }
  void set(const char* name, int v);
  void set(const char* name, unsigned v);
  void set(const char* name, float v);
  void set(const char* name, glm::vec3 v);
  void set(const char* name, glm::ivec2 v);
  void set(const char* name, glm::ivec4 v);

 private:
  struct Deferred {};
  struct Stage {
    GLenum type;
    std::string name;
  };
  // Compiles the stages (`defines` go into the last one) and links, without waiting.
  GlProgram(Deferred, const std::vector<Stage>& stages, const std::string& defines);
  GLint location(const char* name);
  GLuint id_ = 0;
  GLuint shaders_[2] = {0, 0};  // attached until finish() has read their logs; 0: no stage
  std::string names_[2];
  bool finished_ = false;
  std::unordered_map<std::string, GLint> locations_;
};

// True when the current context offers GL_KHR_parallel_shader_compile or
// GL_ARB_parallel_shader_compile (completion can be polled without blocking).
bool has_parallel_shader_compile();

}  // namespace glint
