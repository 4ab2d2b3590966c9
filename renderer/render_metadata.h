// The provenance a final render's image carries in its metadata (renderer/image_metadata.h):
// which Glint made it, from which scene and options, with how many samples and which seed.
#pragma once

#include <cstdint>

#include "renderer/image_metadata.h"
#include "renderer/render_options.h"
#include "renderer/scene.h"

namespace glint {

// The keys, beside "Software" (glint_software(), renderer/build_info.h). The digest is a render
// part's (render_digest, renderer/render_part.h: the scene's radiance and the estimator options
// that change the samples), as 16 hex digits, so an image can be matched with its parts.
inline constexpr const char* kMetadataSoftware = "Software";
inline constexpr const char* kMetadataDigest = "glint.digest";
inline constexpr const char* kMetadataSpp = "glint.spp";
inline constexpr const char* kMetadataSeed = "glint.seed";

// `spp`: the samples per pixel the image holds.
ImageMetadata render_metadata(const Scene& scene, const RenderOptions& options, int64_t spp);

}  // namespace glint
