// The film frame in the viewport: the region that Export writes, fitted inside the viewport at
// the film's aspect (letterbox or pillarbox), and the camera the viewport traces with so that
// this region shows exactly the export's framing while the margins show the scene around it.
//
// The shader's camera (shaders/lib/camera.glsl) spans tan(vfov / 2) over half the image height
// and aspect times that over half its width. The film rect has the film's aspect; if it is as
// tall as the viewport (pillarbox) the viewport camera is the scene's camera; if it is shorter
// (letterbox, e.g. 960x540 film in a portrait viewport) the viewport camera's tan(vfov / 2)
// grows by viewport height / rect height, so that the rect still spans the scene camera's view.
// Pure maths, header only: the viewport renderer (no UI) and the panels both use it.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "renderer/scene.h"

namespace glint {

struct FilmRect {
  glm::vec2 offset{0};  // top-left, relative to the viewport's top-left (viewport units)
  glm::vec2 size{1};
};

// The largest rect of the film's aspect centred in the viewport.
inline FilmRect film_rect(glm::vec2 viewport, const Film& film) {
  const float vw = std::max(viewport.x, 1e-3f), vh = std::max(viewport.y, 1e-3f);
  const float aspect = float(std::max(film.width, 1)) / float(std::max(film.height, 1));
  FilmRect r;
  r.size = vw / vh > aspect ? glm::vec2(vh * aspect, vh) : glm::vec2(vw, vw / aspect);
  r.offset = (glm::vec2(vw, vh) - r.size) * 0.5f;
  return r;
}

// The camera the viewport traces with (and picks and projects with): the scene's camera with
// the field of view widened so that film_rect() shows the export's view.
inline Camera viewport_camera(const Camera& camera, glm::vec2 viewport, const Film& film) {
  Camera c = camera;
  const FilmRect r = film_rect(viewport, film);
  const float grow = std::max(viewport.y, 1e-3f) / std::max(r.size.y, 1e-3f);
  if (grow > 1.0001f) {
    const float tan_half = std::tan(glm::radians(camera.vfov_deg) * 0.5f) * grow;
    c.vfov_deg = glm::degrees(2.0f * std::atan(tan_half));
  }
  return c;
}

}  // namespace glint
