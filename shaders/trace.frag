#version 450 core
// (renderer/shader_features.cpp inserts `#define GLINT_NO_...` lines here for what the scene
// lacks; none defined is the generic program.)
// Path tracing pass as a fragment shader, one fragment per pixel: reads the previous
// accumulation and compensation and writes the next ones (ping-pong render targets).
#include "trace_common.glsl"

layout(binding = 0) uniform sampler2D u_previous;
layout(binding = 3) uniform sampler2D u_previous_compensation;

layout(location = 0) out vec4 out_accumulation;
layout(location = 1) out vec4 out_compensation;

void main() {
  // Texel row y holds image row y (top first), so read-back needs no flip.
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 accumulation = u_samples_before > 0u ? texelFetch(u_previous, pixel, 0) : vec4(0.0);
  vec3 compensation = u_samples_before > 0u ? texelFetch(u_previous_compensation, pixel, 0).rgb : vec3(0.0);
  add_samples(pixel, accumulation, compensation);
  out_accumulation = accumulation;
  out_compensation = vec4(compensation, 0.0);
}
