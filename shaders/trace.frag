#version 450 core
// (renderer/shader_features.cpp inserts `#define GLINT_NO_...` lines here for what the scene
// lacks; none defined is the generic program.)
// Path tracing pass as a fragment shader, one fragment per pixel: reads the previous
// accumulation, variance and their compensations and writes the next ones (ping-pong render
// targets).
// Group votes (GL_ARB_shader_group_vote) let a path whose lane has ended wait for its SIMD group
// (trace_common.glsl, u_restart_together); without them every lane restarts at once.
#extension GL_ARB_shader_group_vote : enable
#if defined(GL_ARB_shader_group_vote)
#define GLINT_GROUP_VOTE
#endif
// Declared before the library's samplers: the first sampler slots (trace_common.glsl says why
// the order matters).
layout(binding = 0) uniform sampler2D u_previous;
layout(binding = 3) uniform sampler2D u_previous_compensation;
layout(binding = 5) uniform sampler2D u_previous_variance;
layout(binding = 6) uniform sampler2D u_previous_variance_compensation;
#include "trace_common.glsl"

layout(location = 0) out vec4 out_accumulation;
layout(location = 1) out vec4 out_compensation;
layout(location = 2) out vec4 out_variance;
layout(location = 3) out vec4 out_variance_compensation;

void main() {
  // Texel row y holds image row y (top first), so read-back needs no flip.
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  bool before = u_samples_before > 0u;
  vec4 accumulation = before ? texelFetch(u_previous, pixel, 0) : vec4(0.0);
  vec4 compensation = before ? texelFetch(u_previous_compensation, pixel, 0) : vec4(0.0);
  vec4 variance_texel = before ? texelFetch(u_previous_variance, pixel, 0) : vec4(0.0);
  vec3 variance = variance_texel.rgb;
  float covered = variance_texel.a;
  vec3 variance_compensation = before ? texelFetch(u_previous_variance_compensation, pixel, 0).rgb : vec3(0.0);
  add_samples(pixel, accumulation, compensation, variance, variance_compensation, covered);
  out_accumulation = accumulation;
  out_compensation = compensation;
  out_variance = vec4(variance, covered);
  out_variance_compensation = vec4(variance_compensation, 0.0);
}
