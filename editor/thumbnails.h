// Small GL textures of image files for the UI (texture slots, the outliner), cached by path.
#pragma once

#include <filesystem>
#include <map>
#include <string>

namespace glint {

class ThumbnailCache {
 public:
  ThumbnailCache() = default;
  ~ThumbnailCache();
  ThumbnailCache(const ThumbnailCache&) = delete;
  ThumbnailCache& operator=(const ThumbnailCache&) = delete;

  // The GL texture name of a thumbnail (at most `size` pixels per side) of this file, or 0 if
  // it cannot be read. Loads on first use; a failed load is remembered, not retried each frame.
  unsigned get(const std::filesystem::path& file, int size = 64);
  void clear();  // drops every texture (needs the GL context that created them)
  size_t size() const { return cache_.size(); }

 private:
  std::map<std::string, unsigned> cache_;
};

}  // namespace glint
