#version 450 core
// The image's error estimate as sums over blocks of pixels (renderer/error_estimate.h): each
// output texel sums a u_block x u_block block of its input. The first pass reads the trace
// pass's textures and sums, per pixel with an estimate (at least two finite samples):
//   r = the pixel's estimated relMSE (trace_common.glsl's estimated_pixel_relmse),
//   g = r / n (its error per finite sample: adaptive sampling's threshold is the mean of it),
//   b = n, the finite samples it holds, a = 1;
// later passes sum the previous pass's sums, until few enough are left to read back.
#include "lib/error_estimate.glsl"

layout(binding = 0) uniform sampler2D u_source;        // accumulation, or the previous sums
layout(binding = 1) uniform sampler2D u_compensation;  // a: samples taken (first pass)
layout(binding = 2) uniform sampler2D u_variance;      // rgb: mean squared deviation (first pass)
uniform bool u_first;
uniform int u_block;
layout(location = 0) out vec4 out_sums;

vec4 pixel_terms(ivec2 p) {
  vec4 accumulation = texelFetch(u_source, p, 0);
  float finite = texelFetch(u_compensation, p, 0).a - accumulation.a;
  float r = estimated_pixel_relmse(accumulation.rgb, texelFetch(u_variance, p, 0).rgb, finite);
  if (r < 0.0) return vec4(0.0);
  return vec4(r, r / finite, finite, 1.0);
}

void main() {
  ivec2 size = textureSize(u_source, 0);
  ivec2 origin = ivec2(gl_FragCoord.xy) * u_block;
  vec4 sums = vec4(0.0);
  for (int y = origin.y; y < min(origin.y + u_block, size.y); ++y)
    for (int x = origin.x; x < min(origin.x + u_block, size.x); ++x)
      sums += u_first ? pixel_terms(ivec2(x, y)) : texelFetch(u_source, ivec2(x, y), 0);
  out_sums = sums;
}
