// Region render (docs/DESIGN.md §3, Region render): the rectangle of the image that a pass
// samples, as Blender's render region. The editor keeps it as fractions of the viewport, so
// that it stays over the same part of the picture when the preview resolution changes; the
// renderer takes it in pixels.
#pragma once

#include <optional>

namespace glint {

// Pixels [x0, x1) x [y0, y1), image rows top first (texel row y is image row y).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
  bool operator==(const PixelRect&) const = default;
};

// A rectangle in fractions of the image: [0, 1]^2, top left (0, 0); the corners in any order.
struct FractionRect {
  float x0 = 0, y0 = 0, x1 = 1, y1 = 1;
  bool operator==(const FractionRect&) const = default;
};

// The pixels of a width x height image that `r` covers: every pixel the rectangle touches,
// clipped to the image, at least one pixel; nullopt for an empty image or a rectangle that
// lies outside it or has no area (or a NaN).
std::optional<PixelRect> region_pixels(const FractionRect& r, int width, int height);

}  // namespace glint
