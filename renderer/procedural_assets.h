// Deterministic procedural textures and a synthetic sky for the example projects (the original
// program's wood/leather/metal and coverage-mask scenes). Everything is computed from integer
// hashes: the same call gives the same pixels on every run, with no random device or clock.
//
// Textures tile seamlessly (noise lattices wrap at the image border), since lookups repeat.
// Colour images hold linear RGB (encode to sRGB before writing 8-bit files); roughness images
// hold linear roughness in all three colour channels, alpha 1.
#pragma once

#include <glm/glm.hpp>

#include "renderer/image.h"

namespace glint::procedural {

Image wood_color(int size = 256);       // warm browns: growth rings plus fine grain
Image wood_roughness(int size = 256);   // rougher in the dark late-wood rings
Image leather_color(int size = 256);    // dark red-brown, pebbled cells, creases and pores
Image leather_roughness(int size = 256);
Image metal_color(int size = 256);      // grey with horizontal brushed streaks
Image metal_roughness(int size = 256);
// An 8x8 checker whose alpha cuts a round hole into every cell (a coverage mask): alpha is 0
// inside the holes, 1 elsewhere, with one anti-aliased pixel at the edge. The colour under a
// hole is the cell colour, so bilinear filtering does not bleed black into the edges.
Image checker_with_holes(int size = 256);

// Lat-long sky, linear HDR: first row is straight up (v = 0 is +Y), a world direction d maps to
// u = atan2(d.z, d.x) / 2pi (wrapped into [0,1)), v = acos(d.y) / pi (docs/DESIGN.md §6).
struct SkyOptions {
  int width = 512;
  int height = 256;
  float sun_elevation_deg = 35;    // above the horizon
  float sun_azimuth_deg = 60;      // atan2(d.z, d.x) in degrees
  float sun_diameter_deg = 8;      // angular diameter of the disc
  float sun_radiance = 80;         // ~290x the median sky: soft shadows, few fireflies without light sampling
  glm::vec3 zenith{0.10f, 0.22f, 0.60f};
  glm::vec3 horizon{0.70f, 0.78f, 0.90f};
  glm::vec3 ground{0.07f, 0.065f, 0.06f};
};

Image sky(const SkyOptions& options = {});

// The unit direction towards the sun's centre.
glm::vec3 sun_direction(const SkyOptions& options);

// The lat-long mapping of docs/DESIGN.md §6 (no rotation): image coordinates in [0,1]^2 to a unit
// direction and back.
glm::vec3 latlong_direction(float u, float v);
glm::vec2 latlong_uv(const glm::vec3& direction);

}  // namespace glint::procedural
