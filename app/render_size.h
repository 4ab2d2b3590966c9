// The image size of a render from the command line's --width/--height and the project's film,
// shared by `glint render` and `glint farm` (which checks parts against the size they render).
#pragma once

#include <optional>
#include <utility>

#include "renderer/scene.h"

namespace glint {

// The project's film size, or the command line's (one side given: the other keeps the film's
// aspect), within the limits of a project's film (check_film_size), so that a size the GPU
// cannot hold is refused before anything is allocated. Throws UsageError (app/command_line.h)
// naming the options for a size beyond the limits.
std::pair<int, int> render_size(std::optional<long> width, std::optional<long> height, const Film& film);

}  // namespace glint
