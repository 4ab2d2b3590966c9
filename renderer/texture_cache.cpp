#include "renderer/texture_cache.h"

#include <sys/stat.h>

#include <list>
#include <mutex>
#include <tuple>
#include <utility>

#include "renderer/scene_images.h"

namespace glint {
namespace {

constexpr size_t kTextureCacheBytes = static_cast<size_t>(kMaxImageBytes);

struct FileIdentity {
  dev_t device = 0;
  ino_t inode = 0;
  off_t size = 0;
  time_t mtime = 0;
  long mtime_ns = 0;
  bool operator==(const FileIdentity& o) const {
    return std::tie(device, inode, size, mtime, mtime_ns) ==
           std::tie(o.device, o.inode, o.size, o.mtime, o.mtime_ns);
  }
};

struct Cache {
  std::mutex mutex;
  // Most recently used first. A handful of entries: a linear search is enough.
  std::list<std::pair<FileIdentity, std::shared_ptr<const TextureImage>>> entries;
  size_t bytes = 0;
  size_t decodes = 0;
};

Cache& cache() {
  static Cache c;
  return c;
}

}  // namespace

std::shared_ptr<const TextureImage> load_texture_cached(const std::filesystem::path& path) {
  struct stat st {};
  // stat follows symlinks: a link and its target are one file. Without an identity (a missing
  // file) the decoder reports the problem.
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
    return std::make_shared<const TextureImage>(load_texture_image(path));
  const FileIdentity id{st.st_dev, st.st_ino, st.st_size, st.st_mtim.tv_sec, st.st_mtim.tv_nsec};
  Cache& c = cache();
  {
    std::lock_guard lock(c.mutex);
    for (auto it = c.entries.begin(); it != c.entries.end(); ++it)
      if (it->first == id) {
        c.entries.splice(c.entries.begin(), c.entries, it);
        return it->second;
      }
  }
  // Decoded outside the lock: another thread may look up other files meanwhile.
  auto image = std::make_shared<const TextureImage>(load_texture_image(path));
  std::lock_guard lock(c.mutex);
  ++c.decodes;
  for (const auto& [other, cached] : c.entries)
    if (other == id) return cached;  // another thread decoded it meanwhile
  c.entries.emplace_front(id, image);
  c.bytes += image->byte_size();
  while (c.bytes > kTextureCacheBytes && c.entries.size() > 1) {
    c.bytes -= c.entries.back().second->byte_size();
    c.entries.pop_back();
  }
  return image;
}

TextureCacheStats texture_cache_stats() {
  Cache& c = cache();
  std::lock_guard lock(c.mutex);
  return {c.decodes, c.entries.size(), c.bytes};
}

}  // namespace glint
