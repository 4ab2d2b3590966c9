#include "editor/thumbnails.h"

#include <algorithm>
#include <vector>

#include <epoxy/gl.h>

#include "renderer/image.h"
#include "renderer/texture_cache.h"

namespace glint {

ThumbnailCache::~ThumbnailCache() { clear(); }

void ThumbnailCache::clear() {
  for (auto& [path, tex] : cache_)
    if (tex) glDeleteTextures(1, &tex);
  cache_.clear();
}

unsigned ThumbnailCache::get(const std::filesystem::path& file, int size) {
  std::string key = file.lexically_normal().string() + "@" + std::to_string(size);
  if (auto it = cache_.find(key); it != cache_.end()) return it->second;
  unsigned tex = 0;
  try {
    // HDR images are tonemapped crudely (clamped) and everything is shown sRGB-encoded. The
    // texels are those the renderer uploads (decoded once, renderer/texture_cache.h).
    const std::shared_ptr<const TextureImage> texture = load_texture_cached(file);
    const TextureImage& img = *texture;
    const int img_w = img.width(), img_h = img.height();
    int w = std::max(1, std::min(size, img_w * size / std::max(img_w, img_h)));
    int h = std::max(1, std::min(size, img_h * size / std::max(img_w, img_h)));
    std::vector<unsigned char> rgba(static_cast<size_t>(w) * h * 4);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        // Box filter over the source block that maps to this thumbnail pixel.
        int x0 = x * img_w / w, x1 = std::max(x0 + 1, (x + 1) * img_w / w);
        int y0 = y * img_h / h, y1 = std::max(y0 + 1, (y + 1) * img_h / h);
        float sum[4] = {0, 0, 0, 0};
        for (int sy = y0; sy < y1; ++sy)
          for (int sx = x0; sx < x1; ++sx)
            for (int c = 0; c < 4; ++c) sum[c] += img.value(sx, sy, c, ColorEncoding::srgb);
        float n = float((x1 - x0) * (y1 - y0));
        for (int c = 0; c < 4; ++c) {
          float v = sum[c] / n;
          if (c < 3) v = linear_to_srgb(std::clamp(v, 0.0f, 1.0f));
          rgba[(static_cast<size_t>(y) * w + x) * 4 + c] =
              static_cast<unsigned char>(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f);
        }
      }
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA8, w, h);
    glTextureSubImage2D(tex, 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  } catch (const std::exception&) {
    tex = 0;
  }
  cache_[key] = tex;
  return tex;
}

}  // namespace glint
