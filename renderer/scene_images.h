// The images a scene names (textures[].path, environment.texture), checked as load_project
// checks them: probed, their memory estimated against kMaxImageBytes before any is decoded,
// then decoded once each (renderer/texture_cache.h), which also checks every texel.
#pragma once

#include <cstdint>
#include <vector>

#include "renderer/project_error.h"
#include "renderer/scene.h"

namespace glint {

// The memory a project may ask for in decoded textures and environment: 4 bytes a texel for
// 8-bit textures, 16 for 16-bit, HDR and EXR textures, and 20 for the environment (its float
// texels and its importance-sampling tables). An 8192x4096 HDR environment (640 MiB) with a
// few 2048x2048 textures fits; a 16384x16384 texture (1 GiB even at 8 bits) does not. The
// renderer keeps this on the GPU and the texture cache once more in main memory.
constexpr int64_t kMaxImageBytes = int64_t(768) << 20;

// The problems of the scene's images (empty when all are readable and within the limit), with
// an empty file name and the JSON path of the image: unreadable or undecodable files, bad
// texels, and the first image that takes the estimate past kMaxImageBytes (with the estimate).
std::vector<ProjectError> check_scene_images(const Scene& scene);

}  // namespace glint
