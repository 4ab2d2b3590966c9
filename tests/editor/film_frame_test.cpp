// The film frame: the viewport's framed region shows exactly what Export writes, and the
// selection outline follows what the renderer draws.
#include <gtest/gtest.h>

#include "editor/film_frame.h"
#include "editor/picking.h"
#include "editor/ui.h"

namespace glint {
namespace {

// Where p lands in the viewport's film rect, in [0,1]^2 of that rect.
glm::vec2 in_frame(const Camera& scene_camera, const Film& film, glm::vec2 viewport, glm::vec3 p) {
  glm::vec2 v;
  EXPECT_TRUE(project_to_viewport(viewport_camera(scene_camera, viewport, film), viewport, p, v));
  const FilmRect r = film_rect(viewport, film);
  return (v - r.offset) / r.size;
}

// Where p lands in the exported image, in [0,1]^2.
glm::vec2 in_export(const Camera& camera, const Film& film, glm::vec3 p) {
  glm::vec2 v;
  EXPECT_TRUE(project_to_viewport(camera, glm::vec2(film.width, film.height), p, v));
  return v / glm::vec2(film.width, film.height);
}

TEST(FilmFrame, RectHasTheFilmsAspectCentredInTheViewport) {
  const Film film{960, 540};
  const FilmRect portrait = film_rect({300, 800}, film);  // letterbox
  EXPECT_FLOAT_EQ(portrait.size.x, 300);
  EXPECT_FLOAT_EQ(portrait.size.y, 300 * 540.0f / 960);
  EXPECT_FLOAT_EQ(portrait.offset.y, (800 - portrait.size.y) / 2);
  const FilmRect wide = film_rect({1600, 500}, film);  // pillarbox
  EXPECT_FLOAT_EQ(wide.size.y, 500);
  EXPECT_FLOAT_EQ(wide.size.x, 500 * 960.0f / 540);
  EXPECT_FLOAT_EQ(wide.offset.x, (1600 - wide.size.x) / 2);
}

TEST(FilmFrame, FramedRegionMatchesTheExportExactly) {
  const Scene scene = new_scene();
  for (Film film : {Film{960, 540}, Film{400, 900}, Film{512, 512}}) {
    for (glm::vec2 viewport : {glm::vec2(300, 800), glm::vec2(1600, 500), glm::vec2(700, 700)}) {
      // Points across the export's view (its corners and centre at several depths) and the
      // scene's objects land at the same place of the frame as of the exported image.
      std::vector<glm::vec3> points = {scene.spheres[0].center, scene.quads[0].corners[3]};
      const Camera& c = scene.camera;
      const glm::vec3 f = glm::normalize(c.target - c.position);
      const glm::vec3 right = glm::normalize(glm::cross(f, c.up)), up = glm::cross(right, f);
      const float th = std::tan(glm::radians(c.vfov_deg) / 2), aspect = float(film.width) / film.height;
      for (float depth : {1.0f, 4.0f})
        for (glm::vec2 s : {glm::vec2(-1, -1), glm::vec2(1, 1), glm::vec2(-1, 1), glm::vec2(0.3f, -0.7f)})
          points.push_back(c.position + depth * (f + s.x * th * aspect * right + s.y * th * up));
      for (glm::vec3 p : points) {
        const glm::vec2 a = in_frame(c, film, viewport, p), b = in_export(c, film, p);
        EXPECT_NEAR(a.x, b.x, 1e-4) << film.width << "x" << film.height << " in " << viewport.x << "x" << viewport.y;
        EXPECT_NEAR(a.y, b.y, 1e-4) << film.width << "x" << film.height << " in " << viewport.x << "x" << viewport.y;
      }
    }
  }
}

TEST(SelectionOutline, SphereOutlineIsItsSilhouetteAsPicked) {
  Scene scene = new_scene();
  const glm::vec2 size(300, 800);  // letterboxed: the widened camera is the one that counts
  const Selection ball{SelectionKind::sphere, 0};
  const std::vector<glm::vec2> outline = selection_outline(scene, ball, size);
  ASSERT_EQ(outline.size(), 64u);
  glm::vec2 centre(0);
  for (glm::vec2 p : outline) centre += p / float(outline.size());
  Scene shown = scene;
  shown.camera = shown_camera(scene, size);
  int inside_hits = 0, outside_hits = 0;
  for (glm::vec2 p : outline) {
    auto at = [&](float s) {
      auto hit = pick(shown, (centre + (p - centre) * s) / size, size.x / size.y);
      return hit && hit->what == ball;
    };
    inside_hits += at(0.97f);
    outside_hits += at(1.03f);
  }
  EXPECT_EQ(inside_hits, 64);
  EXPECT_EQ(outside_hits, 0);
  // A quad: its four corners; nothing for the camera or no selection.
  EXPECT_EQ(selection_outline(scene, {SelectionKind::quad, 0}, size).size(), 4u);
  EXPECT_TRUE(selection_outline(scene, {SelectionKind::camera, -1}, size).empty());
  EXPECT_TRUE(selection_outline(scene, {}, size).empty());
}

}  // namespace
}  // namespace glint
