// Importance sampling of the lat-long environment (docs/DESIGN.md §6) from the tables that
// renderer/environment_distribution.h builds: a marginal CDF over the rows and one conditional
// CDF per row, piecewise constant in (u, v) and proportional to the texels' filtered luminance
// times sin(theta). Needs common.glsl and mapping.glsl.
//
// A lib file cannot declare buffers, so the includer defines these first (trace_common.glsl
// over a table texture, renderer/shader_lib.h over the C++ tables):
//   ivec2 env_distribution_size();               // (width, height) of the image
//   float env_marginal_cdf(int i);               // i in [0, height]: 0 first, exactly 1 last
//   float env_conditional_cdf(int row, int i);   // i in [0, width]: 0 first, exactly 1 last
// Both CDFs are monotone, so a texel's probability is the product of two CDF differences, and
// a texel whose difference rounded to zero is never sampled and has pdf 0 (consistently).
#ifndef GLINT_ENVIRONMENT_SAMPLING_GLSL
#define GLINT_ENVIRONMENT_SAMPLING_GLSL

struct EnvironmentSample {
  vec3 wi;    // world direction, unit
  float pdf;  // solid angle
  bool valid;
};

// The interval [cdf(i), cdf(i + 1)) holding u, for u in [0, 1) and cdf(0) = 0, cdf(n) = 1:
// the returned interval has a non-zero width. row < 0 searches the marginal CDF.
int env_find_interval(int row, int n, float u) {
  int lo = 0;
  int hi = n;
  while (hi - lo > 1) {
    int mid = (lo + hi) / 2;
    float c = row < 0 ? env_marginal_cdf(mid) : env_conditional_cdf(row, mid);
    if (c <= u) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return lo;
}

// The solid-angle pdf of direction d (unit, world space) for the environment rotated by
// `rotation` radians about +Y: texel probability x width x height is the density in (u, v),
// and d omega = 2 pi^2 sin(theta) du dv. sin(theta) = |(d.x, d.z)| does not depend on the
// rotation and has no cancellation near the poles, where it is 0 and the pdf with it.
float environment_pdf(vec3 d, float rotation) {
  ivec2 size = env_distribution_size();
  vec2 uv = environment_uv(d, rotation);
  int x = min(int(uv.x * float(size.x)), size.x - 1);
  int y = min(int(uv.y * float(size.y)), size.y - 1);
  float row_p = env_marginal_cdf(y + 1) - env_marginal_cdf(y);
  float texel_p = env_conditional_cdf(y, x + 1) - env_conditional_cdf(y, x);
  float sin_theta = length(vec2(d.x, d.z));
  if (!(sin_theta > 0.0f)) return 0.0f;
  return row_p * texel_p * float(size.x) * float(size.y) / (2.0f * PI * PI * sin_theta);
}

// u.y picks the row from the marginal CDF, u.x the texel in it from the row's CDF; the rest of
// each number places the direction uniformly in (u, v) inside the texel. The pdf is
// environment_pdf of the returned direction, so the two agree exactly for the same direction.
EnvironmentSample sample_environment(vec2 u, float rotation) {
  ivec2 size = env_distribution_size();
  int y = env_find_interval(-1, size.y, u.y);
  float m0 = env_marginal_cdf(y);
  float dv = (u.y - m0) / (env_marginal_cdf(y + 1) - m0);
  int x = env_find_interval(y, size.x, u.x);
  float c0 = env_conditional_cdf(y, x);
  float du = (u.x - c0) / (env_conditional_cdf(y, x + 1) - c0);
  vec3 local = uv_to_direction(vec2((float(x) + du) / float(size.x), (float(y) + dv) / float(size.y)));
  // environment_uv looks up along d rotated by -rotation; the sample is the local direction
  // rotated by +rotation: (x, z) -> (c x + s z, -s x + c z).
  float c = cos(rotation);
  float s = sin(rotation);
  vec3 wi = normalize(vec3(c * local.x + s * local.z, local.y, -s * local.x + c * local.z));
  float pdf = environment_pdf(wi, rotation);
  return EnvironmentSample(wi, pdf, pdf > 0.0f);
}

#endif
