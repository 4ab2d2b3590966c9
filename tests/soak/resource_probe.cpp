#include "tests/soak/resource_probe.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include <malloc.h>

#include <epoxy/gl.h>

namespace glint::soak {

Resident resident() {
  Resident r;
  std::ifstream status("/proc/self/status");
  std::string line;
  auto field = [&](const char* name, int64_t* out) {  // "VmRSS:   1234 kB"
    const size_t n = std::strlen(name);
    if (line.compare(0, n, name) == 0) *out = std::stoll(line.substr(n));
  };
  while (std::getline(status, line)) {
    field("VmRSS:", &r.total_kib);
    field("RssAnon:", &r.anon_kib);
    field("RssFile:", &r.file_kib);
  }
  return r;
}

int64_t heap_in_use_bytes() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<int64_t>(m.uordblks + m.hblkhd);
}

int64_t heap_held_bytes() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<int64_t>(m.arena + m.hblkhd);
}

GlObjectCounts count_gl_objects() {
  GlObjectCounts c;
  // Probe: the next name of each kind.
  GLuint probe[7] = {};
  glCreateBuffers(1, &probe[0]);
  glCreateTextures(GL_TEXTURE_2D, 1, &probe[1]);
  glCreateFramebuffers(1, &probe[2]);
  glCreateVertexArrays(1, &probe[3]);
  probe[4] = glCreateProgram();
  probe[5] = glCreateShader(GL_FRAGMENT_SHADER);
  glCreateQueries(GL_TIMESTAMP, 1, &probe[6]);
  glDeleteBuffers(1, &probe[0]);
  glDeleteTextures(1, &probe[1]);
  glDeleteFramebuffers(1, &probe[2]);
  glDeleteVertexArrays(1, &probe[3]);
  glDeleteProgram(probe[4]);
  glDeleteShader(probe[5]);
  glDeleteQueries(1, &probe[6]);
  c.highest_probe_name = *std::max_element(probe, probe + 7);
  const GLuint last = std::max<GLuint>(2 * c.highest_probe_name, 65536);
  for (GLuint n = 1; n <= last; ++n) {
    c.buffers += glIsBuffer(n) ? 1 : 0;
    c.textures += glIsTexture(n) ? 1 : 0;
    c.framebuffers += glIsFramebuffer(n) ? 1 : 0;
    c.vertex_arrays += glIsVertexArray(n) ? 1 : 0;
    c.programs += glIsProgram(n) ? 1 : 0;
    c.shaders += glIsShader(n) ? 1 : 0;
    c.queries += glIsQuery(n) ? 1 : 0;
  }
  return c;
}

std::string describe(const GlObjectCounts& c) {
  char text[256];
  std::snprintf(text, sizeof text,
                "%d GL objects (buffers %d, textures %d, framebuffers %d, vertex arrays %d, "
                "programs %d, shaders %d, queries %d; next name %u)",
                c.total(), c.buffers, c.textures, c.framebuffers, c.vertex_arrays, c.programs,
                c.shaders, c.queries, c.highest_probe_name);
  return text;
}

}  // namespace glint::soak
