#version 450 core
// Display pass: mean radiance from the accumulation -> exposure, tonemap, gamma.
// Re-running it never touches the accumulation.
#include "lib/tonemap.glsl"

layout(binding = 0) uniform sampler2D u_accumulation;
uniform float u_exposure;
uniform int u_tonemap;
layout(location = 0) out vec4 out_color;

void main() {
  vec3 mean = texelFetch(u_accumulation, ivec2(gl_FragCoord.xy), 0).rgb;
  out_color = vec4(tonemap(mean, u_exposure, u_tonemap), 1.0);
}
