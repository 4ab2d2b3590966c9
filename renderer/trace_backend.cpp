#include "renderer/trace_backend.h"

#include <cstdlib>

#include "renderer/gl_program.h"

namespace glint {

const char* backend_name(TraceBackend backend) {
  return backend == TraceBackend::compute ? "compute" : "fragment";
}

std::optional<TraceBackend> parse_backend(const std::string& name) {
  if (name == "fragment") return TraceBackend::fragment;
  if (name == "compute") return TraceBackend::compute;
  return std::nullopt;
}

std::optional<WorkGroup> parse_work_group(const std::string& text) {
  const size_t x = text.find('x');
  if (x == std::string::npos || x == 0 || x + 1 >= text.size()) return std::nullopt;
  auto number = [](const std::string& s) -> int {
    if (s.size() > 4 || s.find_first_not_of("0123456789") != std::string::npos) return 0;
    return std::atoi(s.c_str());
  };
  WorkGroup g{number(text.substr(0, x)), number(text.substr(x + 1))};
  if (g.x < 1 || g.y < 1 || g.x * g.y > 1024) return std::nullopt;
  return g;
}

std::string work_group_defines(WorkGroup group) {
  return "#define GLINT_GROUP_X " + std::to_string(group.x) + "\n#define GLINT_GROUP_Y " +
         std::to_string(group.y) + "\n";
}

std::unique_ptr<GlProgram> start_trace_program(TraceBackend backend, WorkGroup group,
                                               const std::string& defines) {
  if (backend == TraceBackend::compute)
    return GlProgram::start_compute("trace.comp", work_group_defines(group) + defines);
  return GlProgram::start("fullscreen.vert", "trace.frag", defines);
}

void bind_trace_images(const TraceTargets& t) {
  const GLuint images[4] = {t.accumulation, t.compensation, t.variance, t.variance_compensation};
  for (GLuint i = 0; i < 4; ++i) glBindImageTexture(i, images[i], 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
}

void dispatch_trace(int width, int height, WorkGroup group) {
  glDispatchCompute(static_cast<GLuint>((width + group.x - 1) / group.x),
                    static_cast<GLuint>((height + group.y - 1) / group.y), 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                  GL_TEXTURE_UPDATE_BARRIER_BIT);
}

void warm_up_compute_pass() {
  GLuint targets[4] = {0, 0, 0, 0};
  glCreateTextures(GL_TEXTURE_2D, 4, targets);
  for (GLuint t : targets) glTextureStorage2D(t, 1, GL_RGBA32F, 1, 1);
  bind_trace_images({targets[0], targets[1], targets[2], targets[3]});
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  glDeleteTextures(4, targets);
}

}  // namespace glint
