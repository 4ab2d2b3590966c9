#version 450 core
// (renderer/shader_features.cpp inserts `#define GLINT_NO_...` lines here for what the scene
// lacks, and renderer/trace_backend.cpp the work-group size.)
// Path tracing pass as a compute shader, one invocation per pixel: the accumulation, the
// variance and their compensations are read and written in place (image load/store, no
// ping-pong); each pixel is read and written by its own invocation only, so no synchronisation
// within a dispatch is needed, and the renderer puts a glMemoryBarrier between dispatches.
// Group votes (GL_ARB_shader_group_vote) let a path whose lane has ended wait for its SIMD group
// (trace_common.glsl, u_restart_together); without them every lane restarts at once.
#extension GL_ARB_shader_group_vote : enable
#if defined(GL_ARB_shader_group_vote)
#define GLINT_GROUP_VOTE
#endif
#ifndef GLINT_GROUP_X
#define GLINT_GROUP_X 8
#endif
#ifndef GLINT_GROUP_Y
#define GLINT_GROUP_Y 8
#endif
#include "trace_common.glsl"

layout(local_size_x = GLINT_GROUP_X, local_size_y = GLINT_GROUP_Y) in;
layout(binding = 0, rgba32f) uniform image2D u_accumulation;
layout(binding = 1, rgba32f) uniform image2D u_compensation;
layout(binding = 2, rgba32f) uniform image2D u_variance;
layout(binding = 3, rgba32f) uniform image2D u_variance_compensation;
// The dispatch covers pixels [u_tile_origin, u_tile_end): the whole image, or one band of rows
// of a pass traced in parts (GpuRenderer::trace_rows).
uniform ivec2 u_tile_origin;
uniform ivec2 u_tile_end;

void main() {
  // Row y of the image is row y of the texture (top first), as in trace.frag.
  ivec2 pixel = u_tile_origin + ivec2(gl_GlobalInvocationID.xy);
  // The last groups' overhang: past the tile (whose next rows the next dispatch traces) or the image.
  if (any(greaterThanEqual(pixel, min(u_tile_end, u_resolution)))) return;
  bool before = u_samples_before > 0u;
  vec4 accumulation = before ? imageLoad(u_accumulation, pixel) : vec4(0.0);
  vec4 compensation = before ? imageLoad(u_compensation, pixel) : vec4(0.0);
  vec4 variance_texel = before ? imageLoad(u_variance, pixel) : vec4(0.0);
  vec3 variance = variance_texel.rgb;
  float covered = variance_texel.a;
  vec3 variance_compensation = before ? imageLoad(u_variance_compensation, pixel).rgb : vec3(0.0);
  add_samples(pixel, accumulation, compensation, variance, variance_compensation, covered);
  imageStore(u_accumulation, pixel, accumulation);
  imageStore(u_compensation, pixel, compensation);
  imageStore(u_variance, pixel, vec4(variance, covered));
  imageStore(u_variance_compensation, pixel, vec4(variance_compensation, 0.0));
}
