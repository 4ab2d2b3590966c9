// Texture lookups of the trace program: material textures, the environment and its
// importance-sampling tables.
// GLSL only, part of the trace program (shaders/trace_common.glsl includes it after the
// shared maths); not compiled as C++ (renderer/shader_lib.h), since it reads the uniforms,
// tables and samplers of the trace program.

#if !defined(GLINT_NO_TEXTURES)
vec4 fetch_texel(ivec4 layer, int x, int y) {
  int i = texel_index(layer, x, y);
  if (layer.w == TEXELS_FLOAT) return texelFetch(u_texels_float, texel_position(i), 0);
  vec4 t = texelFetch(u_texels_8bit, texel_position(i), 0);
  if (layer.w == TEXELS_8BIT_SRGB) t.rgb = vec3(srgb_decode(t.r), srgb_decode(t.g), srgb_decode(t.b));
  return t;
}
#endif

vec4 texture_lookup(int layer, vec2 uv) {
#if defined(GLINT_NO_TEXTURES)
  return vec4(1.0);  // no used material has a texture: every layer is -1
#else
  if (layer < 0) return vec4(1.0);
  ivec4 l = table_texel(u_texture_layer_table, layer);
  BilinearTaps taps = bilinear_taps(uv, l.xy);
  vec4 a = fetch_texel(l, taps.texels.x, taps.texels.y);
  vec4 b = fetch_texel(l, taps.texels.z, taps.texels.y);
  vec4 c = fetch_texel(l, taps.texels.x, taps.texels.w);
  vec4 d = fetch_texel(l, taps.texels.z, taps.texels.w);
  return mix(mix(a, b, taps.weight.x), mix(c, d, taps.weight.x), taps.weight.y);
#endif
}

vec3 environment(vec3 d) {
#if !defined(GLINT_NO_ENV_TEXTURE)
  if (u_env_textured) return u_env_color * texture(u_environment, environment_uv(d, u_env_rotation)).rgb;
#endif
  return u_env_color;
}

// Importance sampling of the environment map: the tables of
// renderer/environment_distribution.h, read by lib/environment_sampling.glsl.
uniform ivec2 u_env_distribution_size;
ivec2 env_distribution_size() { return u_env_distribution_size; }
float env_cdf(int i) { return intBitsToFloat(table_texel(u_env_cdf_table, i).x); }
float env_marginal_cdf(int i) { return env_cdf(i); }
float env_conditional_cdf(int row, int i) {
  return env_cdf(u_env_distribution_size.y + 1 + row * (u_env_distribution_size.x + 1) + i);
}
#include "lib/environment_sampling.glsl"
