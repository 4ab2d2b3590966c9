#include "renderer/trace_draws.h"

#include <algorithm>
#include <vector>

#include "renderer/aov_pass.h"
#include "renderer/film_buffers.h"
#include "renderer/gl_objects.h"
#include "renderer/gl_program.h"
#include "renderer/loop_shapes.h"
#include "renderer/program_worker.h"
#include "renderer/scene_tables.h"
#include "renderer/scene_textures.h"
#include "renderer/trace_uniforms.h"

namespace glint {
namespace {

// The same samples as the colour draw just made, over the same rows, with the scene's tables and
// textures as bind_trace_draw left them.
void trace_aov_draw(AovPass& aovs, const TraceUniforms& uniforms, int samples, int64_t samples_before,
                    int first_row, int rows) {
  GlProgram& p = aovs.program();
  apply_trace_uniforms(p, uniforms);
  p.set("u_samples_before", static_cast<unsigned>(samples_before));
  p.set("u_samples_per_pass", samples);
  aovs.draw(first_row, rows);
}

}  // namespace

GlProgram& bind_trace_draw(GlProgram& p, const TraceBindings& b, const AdaptiveUniforms& adaptive,
                           const TraceDraw& draw) {
  const FilmBuffers& film = b.film;
  apply_trace_uniforms(p, b.uniforms);
  p.set("u_resolution", glm::ivec2(film.width(), film.height()));
  p.set("u_samples_before", static_cast<unsigned>(draw.samples_before));
  p.set("u_samples_per_pass", draw.samples);
  p.set("u_adaptive", adaptive.enabled ? 1 : 0);
  p.set("u_adaptive_threshold", adaptive.threshold);
  p.set("u_adaptive_min_samples", static_cast<unsigned>(std::max(2, adaptive.min_samples)));
  p.set("u_adaptive_every", static_cast<unsigned>(std::max(1, adaptive.every)));
  p.set("u_pass_index", static_cast<unsigned>(draw.pass_index));
  p.set("u_region_on", adaptive.region_on ? 1 : 0);
  p.set("u_region", adaptive.region);
  p.set("u_per_pixel_counts", adaptive.per_pixel_counts ? 1 : 0);
  glUseProgram(p.id());
  b.tables.bind();
  glBindTextureUnit(1, b.textures.texels_8bit());
  glBindTextureUnit(2, b.textures.environment());
  glBindTextureUnit(4, b.textures.texels_float());
  if (b.backend == TraceBackend::compute) {
    bind_trace_images(film.targets(0));
    return p;
  }
  const TraceTargets source = film.targets(draw.source);
  glBindFramebuffer(GL_FRAMEBUFFER, film.framebuffer(1 - draw.source));
  glViewport(0, 0, film.width(), film.height());
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_SCISSOR_TEST);
  glBindTextureUnit(0, source.accumulation);
  glBindTextureUnit(3, source.compensation);
  glBindTextureUnit(5, source.variance);
  glBindTextureUnit(6, source.variance_compensation);
  glBindVertexArray(b.vao);
  return p;
}

BandResult trace_band(GlProgram& program, const TraceBindings& b, const AdaptiveUniforms& adaptive,
                      const TraceDraw& start, const TraceBand& band, AovPass* aovs) {
  const int width = b.film.width();
  const bool whole = band.first == 0 && band.last == b.film.height();
  BandResult result{start.source, 0};
  for (int done = 0; done < band.samples; ++result.draws) {
    const int n = std::min(band.samples - done, band.samples_per_draw);
    const TraceDraw draw{n, start.samples_before + done, start.pass_index + result.draws, result.side};
    GlProgram& p = bind_trace_draw(program, b, adaptive, draw);
    if (b.backend == TraceBackend::compute) {
      p.set("u_tile_origin", glm::ivec2(0, band.first));
      p.set("u_tile_end", glm::ivec2(width, band.last));
      dispatch_trace(width, band.last - band.first, b.work_group);
    } else {
      if (!whole) {
        glEnable(GL_SCISSOR_TEST);
        glScissor(0, band.first, width, band.last - band.first);  // window row y is texel row y
      }
      glDrawArrays(GL_TRIANGLES, 0, 3);
      glDisable(GL_SCISSOR_TEST);
      result.side = 1 - result.side;
    }
    if (aovs) trace_aov_draw(*aovs, b.uniforms, n, draw.samples_before, band.first, band.last - band.first);
    done += n;
  }
  return result;
}

void warm_up_trace_draw(GlProgram& program, const TraceBindings& b, const AdaptiveUniforms& adaptive,
                        const TraceDraw& draw) {
  GlProgram& p = bind_trace_draw(program, b, adaptive, draw);
  if (b.backend == TraceBackend::compute) {
    p.set("u_resolution", glm::ivec2(0, 0));
    glDispatchCompute(1, 1, 1);
    glFinish();
    return;
  }
  glViewport(0, 0, 1, 1);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glFinish();
}

std::shared_ptr<ProgramJob> trace_variant_job(const std::string& defines, const TraceBindings& b) {
  auto job = std::make_shared<ProgramJob>();
  const bool compute = b.backend == TraceBackend::compute;
  if (compute) {
    job->compute = "trace.comp";
    job->defines = work_group_defines(b.work_group) + defines;
  } else {
    job->vertex = "fullscreen.vert";
    job->fragment = "trace.frag";
    job->defines = defines;
  }
  const TraceUniforms uniforms = b.uniforms;
  const TraceTargets film = b.film.targets(b.film.latest());
  const GLuint textures[7] = {film.accumulation, b.textures.texels_8bit(), b.textures.environment(),
                              film.compensation, b.textures.texels_float(), film.variance,
                              film.variance_compensation};
  const std::vector<GLuint> tables = b.tables.textures();
  const GLuint loop_shapes = b.tables.loop_shapes_buffer();
  job->warm_up = [uniforms, textures, tables, loop_shapes, compute](GlProgram& p) {
    apply_trace_uniforms(p, uniforms);
    p.set("u_resolution", glm::ivec2(1, 1));
    p.set("u_samples_before", 0u);
    p.set("u_samples_per_pass", 0);
    for (GLuint i = 0; i < 7; ++i) glBindTextureUnit(i, textures[i]);
    for (GLuint k = 0; k < tables.size(); ++k) glBindTextureUnit(SceneTables::kFirstUnit + k, tables[k]);
    glBindBufferBase(GL_UNIFORM_BUFFER, kLoopShapesBinding, loop_shapes);
    if (compute) {
      warm_up_compute_pass();
      return;
    }
    // Framebuffers are not shared between contexts: a 1x1 one like the film's, here.
    GLuint target[4];
    for (GLuint& t : target) t = make_texture_2d(GL_RGBA32F, 1, 1);
    GLuint fbo = make_trace_framebuffer({target[0], target[1], target[2], target[3]});
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(4, target);
  };
  return job;
}

}  // namespace glint
