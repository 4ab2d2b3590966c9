#include "renderer/scene_tables.h"

#include <algorithm>
#include <bit>
#include <limits>
#include <stdexcept>

#include "renderer/bvh.h"
#include "renderer/loop_shapes.h"

namespace glint {
namespace {

// Texels that a buffer texture holds (GL_MAX_TEXTURE_BUFFER_SIZE), or `option` when positive
// (tests); at most INT_MAX.
int64_t table_limit(int64_t option) {
  int64_t limit = option;
  if (limit <= 0) {
    GLint max_texels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    limit = max_texels;
  }
  return std::min<int64_t>(limit, std::numeric_limits<int>::max());
}

}  // namespace

void check_table_texels(const std::string& what, size_t count, int64_t texels, int64_t limit) {
  if (texels > limit)
    throw std::runtime_error(what + " (" + std::to_string(count) + ") need " + std::to_string(texels) +
                             " texels, more than this OpenGL driver holds (" + std::to_string(limit) +
                             " texels in a table: GL_MAX_TEXTURE_BUFFER_SIZE)");
}

SceneTables::SceneTables(int64_t max_texels) : max_texels_(table_limit(max_texels)) {
  glCreateTextures(GL_TEXTURE_BUFFER, kCount, textures_);
  glCreateBuffers(kCount, buffers_);
  glCreateBuffers(1, &loop_shapes_buffer_);
  const LoopShapesBlock empty;
  glNamedBufferData(loop_shapes_buffer_, sizeof empty, &empty, GL_DYNAMIC_DRAW);
  upload(SceneTable::spheres, std::vector<GpuSphere>{});
  upload(SceneTable::quads, std::vector<GpuQuad>{});
  upload(SceneTable::materials, std::vector<GpuMaterial>{});
  upload(SceneTable::layers, std::vector<glm::ivec4>{});
  upload(SceneTable::lights, std::vector<GpuLight>{});
  upload(SceneTable::environment, std::vector<float>{});
  upload(SceneTable::bvh_nodes, std::vector<GpuBvhNode>{});
  upload(SceneTable::bvh_primitives, std::vector<int32_t>{});
}

SceneTables::~SceneTables() {
  glDeleteTextures(kCount, textures_);
  glDeleteBuffers(kCount, buffers_);
  glDeleteBuffers(1, &loop_shapes_buffer_);
}

// The buffer is a power of two of bytes, at least 64 KiB, zeros past the data: llvmpipe keys its
// compiled shaders by whether each bound texture's size is a power of two, and by bits 8 to 15 of
// a buffer texture's byte size (which alias a 2-D texture's last mipmap level in gallium's sampler
// view), so that with any other size a draw could compile the program again, on the calling
// thread, after the worker's warm-up draw (program_worker.h) had compiled it for another size.
// The zeros also stand for the empty table's one element (a lane masked off may still read it).
// The texture and the buffer keep their names (a warm-up job holds them).
void SceneTables::upload_bytes(SceneTable table, const void* data, int64_t bytes, bool rgba) {
  const int k = static_cast<int>(table);
  const int64_t size = std::max<int64_t>(int64_t(1) << 16, std::bit_ceil(static_cast<uint64_t>(bytes)));
  glNamedBufferData(buffers_[k], static_cast<GLsizeiptr>(size), nullptr, GL_STATIC_DRAW);
  glClearNamedBufferData(buffers_[k], GL_R32I, GL_RED_INTEGER, GL_INT, nullptr);
  if (bytes > 0) glNamedBufferSubData(buffers_[k], 0, static_cast<GLsizeiptr>(bytes), data);
  glTextureBuffer(textures_[k], rgba ? GL_RGBA32I : GL_R32I, buffers_[k]);
}

void SceneTables::upload_loop_shapes(const std::vector<GpuSphere>& spheres, const std::vector<GpuQuad>& quads) {
  const LoopShapesBlock block = loop_shapes_block(spheres, quads);
  glNamedBufferSubData(loop_shapes_buffer_, 0, sizeof block, &block);
}

void SceneTables::bind() const {
  for (GLuint k = 0; k < kCount; ++k) glBindTextureUnit(kFirstUnit + k, textures_[k]);
  glBindBufferBase(GL_UNIFORM_BUFFER, kLoopShapesBinding, loop_shapes_buffer_);
}

GeometryCounts upload_geometry(SceneTables& tables, const PackedScene& packed) {
  tables.check_size("spheres", packed.spheres);
  tables.check_size("quads", packed.quads);
  tables.check_size("materials", packed.materials);
  tables.check_size("lights", packed.lights);
  tables.upload(SceneTable::spheres, packed.spheres);
  tables.upload(SceneTable::quads, packed.quads);
  tables.upload(SceneTable::materials, packed.materials);
  tables.upload(SceneTable::lights, packed.lights);
  tables.upload_loop_shapes(packed.spheres, packed.quads);
  return {static_cast<int>(packed.spheres.size()), static_cast<int>(packed.quads.size()),
          static_cast<int>(packed.lights.size())};
}

}  // namespace glint
