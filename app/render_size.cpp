#include "app/render_size.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "app/command_line.h"
#include "renderer/scene_validation.h"

namespace glint {

std::pair<int, int> render_size(std::optional<long> width_option, std::optional<long> height_option,
                                const Film& film) {
  if (!width_option && !height_option) return {film.width, film.height};  // checked by the loader
  int64_t width = film.width, height = film.height;
  if (width_option) width = *width_option;
  if (height_option) height = *height_option;
  if (width_option && !height_option)
    height = std::max<int64_t>(1, std::llround(*width_option * double(film.height) / film.width));
  if (height_option && !width_option)
    width = std::max<int64_t>(1, std::llround(*height_option * double(film.width) / film.height));
  if (const auto problem = check_film_size(width, height)) {
    const std::string& key = problem->json_path;
    std::string given;
    if (width_option) given += "--width " + std::to_string(*width_option);
    if (height_option) given += (given.empty() ? "" : " ") + ("--height " + std::to_string(*height_option));
    throw UsageError{given + " gives a " + std::to_string(width) + "x" + std::to_string(height) +
                     " image: " +
                     (key == "film.width" ? "the width " : key == "film.height" ? "the height " : "") +
                     problem->problem};
  }
  return {static_cast<int>(width), static_cast<int>(height)};
}

}  // namespace glint
