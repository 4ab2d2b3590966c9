#include "renderer/render_metadata.h"

#include <cinttypes>
#include <cstdio>
#include <string>

#include "renderer/build_info.h"
#include "renderer/render_part.h"

namespace glint {

ImageMetadata render_metadata(const Scene& scene, const RenderOptions& options, int64_t spp) {
  char digest[17];
  std::snprintf(digest, sizeof digest, "%016" PRIx64, render_digest(scene, options));
  return {{kMetadataSoftware, glint_software()},
          {kMetadataDigest, digest},
          {kMetadataSpp, std::to_string(spp)},
          {kMetadataSeed, std::to_string(scene.render.seed)}};
}

}  // namespace glint
