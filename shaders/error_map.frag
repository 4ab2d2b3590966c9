#version 450 core
// The live error map (renderer/error_map.h): each pixel's estimated relMSE (the one the image's
// error figure averages, lib/error_estimate.glsl) as a heat colour on a log scale, for the
// viewport's overlay. Pixels without an estimate (fewer than two finite samples) are
// transparent.
#include "lib/error_estimate.glsl"

layout(binding = 0) uniform sampler2D u_accumulation;  // rgb mean, a discarded
layout(binding = 1) uniform sampler2D u_compensation;  // a: samples taken
layout(binding = 2) uniform sampler2D u_variance;      // rgb: mean squared deviation
uniform float u_log_low;   // log10 of the relMSE shown coldest
uniform float u_log_high;  // ... and hottest
uniform float u_opacity;
layout(location = 0) out vec4 out_colour;

// Blue, cyan, green, yellow, red at t = 0, 1/4, 1/2, 3/4, 1.
vec3 heat(float t) {
  const vec3 stops[5] = vec3[5](vec3(0.1, 0.2, 1.0), vec3(0.0, 0.9, 1.0), vec3(0.1, 0.9, 0.2),
                                vec3(1.0, 0.9, 0.0), vec3(1.0, 0.1, 0.05));
  float x = clamp(t, 0.0, 1.0) * 4.0;
  int i = min(int(x), 3);
  return mix(stops[i], stops[i + 1], x - float(i));
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 accumulation = texelFetch(u_accumulation, p, 0);
  float finite = texelFetch(u_compensation, p, 0).a - accumulation.a;
  float r = estimated_pixel_relmse(accumulation.rgb, texelFetch(u_variance, p, 0).rgb, finite);
  if (r < 0.0) {
    out_colour = vec4(0.0);
    return;
  }
  float t = (log(max(r, 1e-30)) / log(10.0) - u_log_low) / (u_log_high - u_log_low);
  out_colour = vec4(heat(t), u_opacity);
}
