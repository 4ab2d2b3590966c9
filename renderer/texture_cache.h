// Decoded textures shared by the project loader, the renderer and the editor's thumbnails, so
// that each image file is decoded once: load_project decodes (and so fully checks) every image
// it names, and the renderer then uploads the same decoded texels. Entries are keyed by file
// identity (device, inode, size and modification time), so one file named by several paths
// (a.png, ./a.png, a symlink) is one entry, and a file that changes on disk is decoded again.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>

#include "renderer/image.h"

namespace glint {

// The decoded image of `path` (load_texture_image), from the cache when the file is unchanged.
// Throws ImageError as load_texture_image does; failures are not cached. Thread-safe.
std::shared_ptr<const TextureImage> load_texture_cached(const std::filesystem::path& path);

// The cache keeps the most recently used images up to kTextureCacheBytes (as much as one
// project may ask for, kMaxImageBytes of scene_images.h); older ones are dropped from it and
// freed once no renderer holds them.
struct TextureCacheStats {
  size_t decodes = 0;  // files decoded since the program started
  size_t entries = 0;
  size_t bytes = 0;
};
TextureCacheStats texture_cache_stats();

}  // namespace glint
