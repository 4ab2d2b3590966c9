// The limits of a scene and its validation (docs/DESIGN.md §6): what the loader checks after
// parsing and the editor after every edit. The file format (project_file.h) is not involved:
// a scene built through the API is checked the same way.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "renderer/project_error.h"
#include "renderer/scene.h"

namespace glint {

// Limits of a scene, checked on load and by validate_scene (docs/DESIGN.md §6 lists them).
//  - Film: at most kMaxFilmSide pixels per side (the GL_MAX_TEXTURE_SIZE of llvmpipe and common
//    GPUs) and kMaxFilmPixels in all. The renderer keeps kFilmBytesPerPixel of GPU memory per
//    pixel (two RGBA32F accumulation textures, two RGBA32F compensation textures and an RGBA8
//    display texture), so the largest film takes 4.25 GiB; a larger one is refused with its
//    memory estimate, never attempted.
//  - Spheres and quads: at most kMaxSpheres and kMaxQuads each (2^20; 10^6 spheres load). Their
//    tables (2 and 8 texels of 16 bytes an element) then stay within 2^23 texels, well inside
//    the 2^28 a table holds where GL_MAX_TEXTURE_SIZE is 16384 (the renderer refuses a table
//    beyond its driver's limit). A longer array is refused before any of its elements is
//    read.
// (project_file.h adds the limit of the file's size.)
constexpr int kMaxFilmSide = 16384;
constexpr int64_t kMaxFilmPixels = int64_t(1) << 26;  // e.g. 8192 x 8192
constexpr int kFilmBytesPerPixel = 4 * 16 + 4;
constexpr size_t kMaxSpheres = size_t(1) << 20;
constexpr size_t kMaxQuads = size_t(1) << 20;
// Camera views (bookmarks) a project may hold: far more than anyone names by hand.
constexpr size_t kMaxCameraViews = 1024;

// Validates a scene as the loader would (used after edits through the UI or the API).
// Returns the problems as ProjectErrors with an empty file name; empty when valid. The value
// checks of each field are those of its table (scene_fields.h). A quad has zero area when
// either triangle's |cross(e1, e2)| <= 1e-12 * scale^2 (scale: the largest distance between
// two corners); camera.up is parallel when |sin| of its angle <= 1e-6.
std::vector<ProjectError> validate_scene(const Scene& scene, bool check_files = true);

// The problem with a width x height film (file name empty; JSON path film.width, film.height or
// film), or nullopt when it is within the limits above. Sizes too large say how much GPU memory
// they would take: "film.width: must be an integer in [1, 16384] (got 100000); a 100000x100000
// film would need 633.3 GiB of GPU buffers (68 bytes per pixel), the limit is 4.2 GiB
// (67108864 pixels, e.g. 8192x8192)".
std::optional<ProjectError> check_film_size(int64_t width, int64_t height);

// "too many spheres: 2000000 (the limit is 1048576, so that ...)": a list over its limit.
std::string too_many_problem(size_t count, size_t limit, const char* what);

// "too many views: 2000 (the limit is 1024)".
std::string too_many_views_problem(size_t count);

// "335.3 GiB", "512.0 MiB": memory sizes in messages.
std::string bytes_text(double bytes);

}  // namespace glint
