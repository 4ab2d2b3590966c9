// Procedural textures and sky (see procedural_assets.h). All noise is built from one integer
// hash, so the output depends on nothing but the code: no random device, no clock, no state.
#include "renderer/procedural_assets.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>

namespace glint::procedural {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// --- noise ---------------------------------------------------------------------------------------

// Integer hash of a lattice point (a "lowbias32" finaliser over a linear mix of the inputs).
uint32_t hash(uint32_t x, uint32_t y, uint32_t seed) {
  uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ (seed + 1) * 0xcb1ab31fu;
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return h;
}

float hash01(uint32_t x, uint32_t y, uint32_t seed) {
  return static_cast<float>(hash(x, y, seed) >> 8) * (1.0f / 16777216.0f);  // [0, 1)
}

int wrap(int i, int period) {
  const int m = i % period;
  return m < 0 ? m + period : m;
}

float fade(float t) { return t * t * t * (t * (t * 6 - 15) + 10); }  // C2 smooth interpolation
float mix(float a, float b, float t) { return a + (b - a) * t; }
float fract(float x) { return x - std::floor(x); }
float smoothstep(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3 - 2 * t);
}

// Value noise in [0,1) at (x, y) in lattice units; the lattice repeats every (px, py) cells, so
// noise sampled at u * px over u in [0,1) tiles seamlessly.
float value_noise(float x, float y, int px, int py, uint32_t seed) {
  const float fx = std::floor(x), fy = std::floor(y);
  const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
  const float tx = fade(x - fx), ty = fade(y - fy);
  auto at = [&](int i, int j) {
    return hash01(static_cast<uint32_t>(wrap(i, px)), static_cast<uint32_t>(wrap(j, py)), seed);
  };
  return mix(mix(at(ix, iy), at(ix + 1, iy), tx), mix(at(ix, iy + 1), at(ix + 1, iy + 1), tx), ty);
}

// Fractal sum of value noise over texture coordinates (u, v) in [0,1), normalised to [0,1).
// (px, py) is the lattice of the first octave; each octave doubles it, so tiling is kept.
float fbm(float u, float v, int px, int py, int octaves, uint32_t seed) {
  float sum = 0, amplitude = 0.5f, norm = 0;
  for (int i = 0; i < octaves; ++i) {
    const int qx = px << i, qy = py << i;
    sum += amplitude * value_noise(u * qx, v * qy, qx, qy, seed + 101 * i);
    norm += amplitude;
    amplitude *= 0.5f;
  }
  return sum / norm;
}

// Cellular (Worley) noise: distances to the nearest and second-nearest jittered feature points,
// in cell units, on a period x period lattice over (u, v) in [0,1).
struct Cells {
  float f1 = 1e9f, f2 = 1e9f;
  uint32_t id = 0;  // hash of the nearest cell
};

Cells cellular(float u, float v, int period, uint32_t seed) {
  const float x = u * period, y = v * period;
  const int ix = static_cast<int>(std::floor(x)), iy = static_cast<int>(std::floor(y));
  Cells cells;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int cx = ix + dx, cy = iy + dy;
      const auto wx = static_cast<uint32_t>(wrap(cx, period));
      const auto wy = static_cast<uint32_t>(wrap(cy, period));
      // Jitter kept inside [0.1, 0.9] so that cells stay roughly even in size.
      const float fx = cx + 0.1f + 0.8f * hash01(wx, wy, seed);
      const float fy = cy + 0.1f + 0.8f * hash01(wx, wy, seed + 1);
      const float d = std::hypot(x - fx, y - fy);
      if (d < cells.f1) {
        cells.f2 = cells.f1;
        cells.f1 = d;
        cells.id = hash(wx, wy, seed + 2);
      } else if (d < cells.f2) {
        cells.f2 = d;
      }
    }
  return cells;
}

// --- image helpers -------------------------------------------------------------------------------

glm::vec3 srgb(float r, float g, float b) {  // a colour picked by eye, as linear RGB
  return {srgb_to_linear(r), srgb_to_linear(g), srgb_to_linear(b)};
}

// Fills an RGBA image from f(u, v) evaluated at pixel centres.
Image generate(int size, const std::function<glm::vec4(float, float)>& f) {
  Image image = Image::filled(size, size, 1.0f);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const glm::vec4 c = f((x + 0.5f) / size, (y + 0.5f) / size);
      float* p = image.at(x, y);
      p[0] = c.r, p[1] = c.g, p[2] = c.b, p[3] = c.a;
    }
  return image;
}

glm::vec4 grey(float value) {
  const float g = std::clamp(value, 0.0f, 1.0f);
  return {g, g, g, 1};
}

// --- wood ----------------------------------------------------------------------------------------

struct Wood {
  float late;   // 1 in the dark late-wood band of a growth ring
  float grain;  // fine streaks along the fibres, around 0.5
  float tone;   // slow variation of the whole board, around 0.5
};

// The fibres run along v; u crosses the rings. An integer ring count keeps the texture tiling.
Wood wood_field(float u, float v) {
  // Slow bends along the board (lattice 2 x 1) and a little wobble across it.
  const float warp = fbm(u, v, 2, 1, 3, 11);
  const float wobble = fbm(u, v, 8, 4, 2, 13);
  const float ring = u * 9 + (warp - 0.5f) * 1.6f + (wobble - 0.5f) * 0.35f;
  const float t = fract(ring);
  // Early wood lightens slowly across the ring; late wood is a narrower dark band with a sharp
  // edge where the next year's growth starts.
  const float late = smoothstep(0.55f, 0.88f, t) * (1 - smoothstep(0.9f, 0.98f, t));
  const float grain = 0.65f * fbm(u, v, 64, 4, 3, 23) + 0.35f * value_noise(u * 128, v * 6, 128, 6, 29);
  return {late, grain, fbm(u, v, 2, 2, 3, 37)};
}

// --- leather -------------------------------------------------------------------------------------

struct Leather {
  float crease;  // 1 in the creases between pebbles
  float dome;    // 1 at a pebble's centre, falling towards its edge
  float pore;    // 1 inside a pore
  float tone;    // slow variation, around 0.5
  float cell;    // per-pebble random value in [0,1)
};

Leather leather_field(float u, float v) {
  // Domain-warp the pebbles a little so that they are not perfect Voronoi polygons.
  const float wu = u + 0.015f * (fbm(u, v, 8, 8, 2, 51) - 0.5f);
  const float wv = v + 0.015f * (fbm(u, v, 8, 8, 2, 53) - 0.5f);
  const Cells pebbles = cellular(wu, wv, 36, 31);
  const Cells pores = cellular(u, v, 110, 41);
  // Large soft wrinkles deepen some creases and fade others.
  const float wrinkle = fbm(u, v, 4, 4, 3, 57);
  Leather l;
  l.crease = (1 - smoothstep(0.0f, 0.12f, pebbles.f2 - pebbles.f1)) * (0.4f + 0.9f * wrinkle);
  l.dome = 1 - std::clamp(pebbles.f1 / 0.7f, 0.0f, 1.0f);
  // Only some lattice cells hold a pore, and pores vary in size.
  const float has_pore = (pores.id & 0xffu) < 110 ? 1.0f : 0.0f;
  const float radius = 0.10f + 0.08f * static_cast<float>((pores.id >> 8) & 0xffu) / 255.0f;
  l.pore = has_pore * (1 - smoothstep(radius * 0.6f, radius, pores.f1));
  l.tone = fbm(u, v, 3, 3, 4, 61);
  l.cell = static_cast<float>(pebbles.id >> 8) * (1.0f / 16777216.0f);
  return l;
}

// --- brushed metal -------------------------------------------------------------------------------

struct Metal {
  float streak;   // brushing streaks along u, around 0.5
  float scratch;  // sparse brighter scratches, 0 or up to 1
  float blotch;   // large, faint variation, around 0.5
};

Metal metal_field(float u, float v) {
  Metal m;
  // Lattices long in u and short in v give thin horizontal streaks.
  m.streak = 0.55f * fbm(u, v, 2, 96, 3, 71) + 0.45f * value_noise(u * 4, v * 256, 4, 256, 73);
  // A scratch is a one-row line on some of the rows, fading along its length.
  const float row = value_noise(u * 3, v * 512, 3, 512, 79);
  m.scratch = smoothstep(0.82f, 0.95f, row);
  m.blotch = fbm(u, v, 3, 3, 3, 83);
  return m;
}

}  // namespace

// --- public generators ---------------------------------------------------------------------------

Image wood_color(int size) {
  const glm::vec3 light = srgb(0.80f, 0.58f, 0.36f), dark = srgb(0.42f, 0.22f, 0.10f);
  return generate(size, [&](float u, float v) {
    const Wood w = wood_field(u, v);
    const float t = std::clamp(0.9f * w.late + 0.6f * (w.grain - 0.5f), 0.0f, 1.0f);
    const glm::vec3 c = glm::mix(light, dark, t) * (0.85f + 0.3f * w.tone);
    return glm::vec4(c, 1);
  });
}

Image wood_roughness(int size) {
  return generate(size, [](float u, float v) {
    const Wood w = wood_field(u, v);
    return grey(0.5f + 0.2f * w.late + 0.25f * (w.grain - 0.5f));
  });
}

Image leather_color(int size) {
  const glm::vec3 base = srgb(0.36f, 0.16f, 0.10f), deep = srgb(0.17f, 0.07f, 0.045f);
  return generate(size, [&](float u, float v) {
    const Leather l = leather_field(u, v);
    glm::vec3 c = base * (0.75f + 0.35f * l.dome + 0.12f * (l.cell - 0.5f));
    c = glm::mix(c, deep, std::min(0.6f * l.crease, 1.0f));
    c = glm::mix(c, deep * 0.6f, 0.8f * l.pore);
    return glm::vec4(c * (0.85f + 0.3f * l.tone), 1);
  });
}

Image leather_roughness(int size) {
  return generate(size, [](float u, float v) {
    const Leather l = leather_field(u, v);
    return grey(0.5f - 0.1f * l.dome + 0.25f * l.crease + 0.2f * l.pore + 0.1f * (l.tone - 0.5f));
  });
}

Image metal_color(int size) {
  const glm::vec3 steel = srgb(0.66f, 0.67f, 0.70f);
  return generate(size, [&](float u, float v) {
    const Metal m = metal_field(u, v);
    const float k = 0.82f + 0.3f * m.streak + 0.12f * m.scratch + 0.1f * (m.blotch - 0.5f);
    return glm::vec4(glm::min(steel * k, glm::vec3(1)), 1);
  });
}

Image metal_roughness(int size) {
  return generate(size, [](float u, float v) {
    const Metal m = metal_field(u, v);
    return grey(0.25f + 0.2f * (m.streak - 0.5f) - 0.08f * m.scratch + 0.1f * (m.blotch - 0.5f));
  });
}

Image checker_with_holes(int size) {
  const glm::vec3 light = srgb(0.90f, 0.88f, 0.82f), dark = srgb(0.70f, 0.12f, 0.10f);
  const int cells = 8;
  const float cell = static_cast<float>(size) / cells;
  const float radius = 0.3f * cell;
  Image image = Image::filled(size, size, 1.0f);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float px = x + 0.5f, py = y + 0.5f;
      const int cx = static_cast<int>(px / cell), cy = static_cast<int>(py / cell);
      const float dist = std::hypot(px - (cx + 0.5f) * cell, py - (cy + 0.5f) * cell);
      const glm::vec3 c = (cx + cy) % 2 == 0 ? light : dark;
      float* p = image.at(x, y);
      p[0] = c.r, p[1] = c.g, p[2] = c.b;
      // Coverage of the pixel by the surface, a one-pixel ramp across the hole's rim.
      p[3] = std::clamp(dist - radius + 0.5f, 0.0f, 1.0f);
    }
  return image;
}

glm::vec3 latlong_direction(float u, float v) {
  const float phi = 2 * kPi * u, theta = kPi * v;
  return {std::cos(phi) * std::sin(theta), std::cos(theta), std::sin(phi) * std::sin(theta)};
}

glm::vec2 latlong_uv(const glm::vec3& d) {
  float u = std::atan2(d.z, d.x) / (2 * kPi);
  if (u < 0) u += 1;
  if (u >= 1) u -= 1;
  return {u, std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi};
}

glm::vec3 sun_direction(const SkyOptions& o) {
  const float e = glm::radians(o.sun_elevation_deg), a = glm::radians(o.sun_azimuth_deg);
  return {std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a)};
}

Image sky(const SkyOptions& o) {
  const glm::vec3 sun = sun_direction(o);
  const float sun_cos = std::cos(glm::radians(0.5f * o.sun_diameter_deg));
  const glm::vec3 sun_tint(1.0f, 0.95f, 0.86f);
  auto radiance = [&](const glm::vec3& d) {
    const float y = d.y;
    const float cos_sun = glm::dot(d, sun);
    const float angle = std::acos(std::clamp(cos_sun, -1.0f, 1.0f));
    // Above: zenith blue brightening to a pale horizon, plus a soft glow around the sun.
    glm::vec3 above = glm::mix(o.zenith, o.horizon, std::pow(1 - std::max(y, 0.0f), 4.0f));
    above += sun_tint * (1.5f * std::exp(-angle / 0.06f) + 0.25f * std::exp(-angle / 0.5f));
    // Below: dark ground, a little lighter towards the horizon haze.
    const glm::vec3 below =
        glm::mix(o.ground, o.ground * 2.5f, std::pow(1 - std::min(-y, 1.0f), 16.0f));
    glm::vec3 c = glm::mix(below, above, smoothstep(-0.01f, 0.01f, y));
    if (cos_sun >= sun_cos) c += sun_tint * o.sun_radiance;
    return c;
  };
  // 4x4 samples per pixel: the sun is only a few pixels wide and must not alias.
  constexpr int kSub = 4;
  Image image = Image::filled(o.width, o.height, 1.0f);
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x) {
      glm::vec3 sum(0);
      for (int j = 0; j < kSub; ++j)
        for (int i = 0; i < kSub; ++i)
          sum += radiance(latlong_direction((x + (i + 0.5f) / kSub) / o.width,
                                            (y + (j + 0.5f) / kSub) / o.height));
      const glm::vec3 c = sum / static_cast<float>(kSub * kSub);
      float* p = image.at(x, y);
      p[0] = c.r, p[1] = c.g, p[2] = c.b;
    }
  return image;
}

}  // namespace glint::procedural
