#include "renderer/sample_region.h"

#include <algorithm>
#include <cmath>

namespace glint {

std::optional<PixelRect> region_pixels(const FractionRect& r, int width, int height) {
  if (width <= 0 || height <= 0) return std::nullopt;
  const float lo_x = std::min(r.x0, r.x1), hi_x = std::max(r.x0, r.x1);
  const float lo_y = std::min(r.y0, r.y1), hi_y = std::max(r.y0, r.y1);
  if (!(hi_x > lo_x && hi_y > lo_y) || !(hi_x > 0 && lo_x < 1 && hi_y > 0 && lo_y < 1))
    return std::nullopt;  // also NaN: every comparison is false
  auto side = [](float lo, float hi, int n, int& a, int& b) {
    a = std::clamp(static_cast<int>(std::floor(lo * n)), 0, n - 1);
    b = std::clamp(static_cast<int>(std::ceil(hi * n)), a + 1, n);
  };
  PixelRect p;
  side(lo_x, hi_x, width, p.x0, p.x1);
  side(lo_y, hi_y, height, p.y0, p.y1);
  return p;
}

}  // namespace glint
