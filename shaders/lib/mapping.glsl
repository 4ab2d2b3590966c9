// Texture-coordinate conventions of docs/DESIGN.md §6 and bilinear, repeating texel look-ups.
#ifndef GLINT_MAPPING_GLSL
#define GLINT_MAPPING_GLSL

// u = atan2(d.z, d.x) / 2pi wrapped into [0,1), v = acos(d.y) / pi; d must be unit length.
vec2 direction_to_uv(vec3 d) {
  float u = atan(d.z, d.x) * (1.0f / TWO_PI);
  if (u < 0.0f) u += 1.0f;
  if (u >= 1.0f) u = 0.0f;  // -0 and tiny negatives round up to exactly 1
  float v = acos(clamp(d.y, -1.0f, 1.0f)) * INV_PI;
  return vec2(u, v);
}

vec3 uv_to_direction(vec2 uv) {
  float phi = uv.x * TWO_PI;
  float theta = uv.y * PI;
  return vec3(cos(phi) * sin(theta), cos(theta), sin(phi) * sin(theta));
}

// The environment rotated by `rotation` radians about +Y, seen along world direction d.
vec2 environment_uv(vec3 d, float rotation) {
  float c = cos(rotation);
  float s = sin(rotation);
  // Rotating the environment by +r is looking it up along d rotated by -r. Right-handed
  // rotation about +Y by r maps (x, z) to (c x + s z, -s x + c z) (+Z towards +X), so by -r:
  vec3 local = vec3(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
  return direction_to_uv(local);
}

// Bilinear filtering on a w x h texel grid with repeat wrapping. Texel centres sit at
// (i + 0.5) / w; v = 0 is the first row. The four taps are (x0,y0) (x1,y0) (x0,y1) (x1,y1).
struct BilinearTaps {
  ivec4 texels;  // x0, y0, x1, y1, all inside the grid
  vec2 weight;   // fractional position between x0 and x1, y0 and y1
};

int wrap_index(int i, int n) {
  int r = i % n;
  return r < 0 ? r + n : r;
}

BilinearTaps bilinear_taps(vec2 uv, ivec2 size) {
  float x = (uv.x - floor(uv.x)) * float(size.x) - 0.5f;
  float y = (uv.y - floor(uv.y)) * float(size.y) - 0.5f;
  float fx = floor(x);
  float fy = floor(y);
  int x0 = wrap_index(int(fx), size.x);
  int y0 = wrap_index(int(fy), size.y);
  return BilinearTaps(ivec4(x0, y0, wrap_index(x0 + 1, size.x), wrap_index(y0 + 1, size.y)),
                      vec2(x - fx, y - fy));
}

// Where a texture's texels are (renderer/gpu_renderer.cpp, upload_textures): one sequence of
// texels for 8-bit textures (RGBA8 as stored) and one for float ones (RGBA32F), each texture a
// row-major run of texels in one of them; texel_index is the position in the sequence. Its
// layer record is (width, height, first texel, kind); 8-bit sRGB texels are decoded per tap with
// srgb_decode.
const int TEXELS_8BIT_LINEAR = 0;
const int TEXELS_8BIT_SRGB = 1;
const int TEXELS_FLOAT = 2;

int texel_index(ivec4 layer, int x, int y) { return layer.z + y * layer.x + x; }

// sRGB-encoded value to linear (IEC 61966-2-1), as srgb_to_linear in renderer/image_io.cpp.
float srgb_decode(float c) {
  if (c <= 0.04045f) return c / 12.92f;
  return pow((c + 0.055f) / 1.055f, 2.4f);
}

#endif
