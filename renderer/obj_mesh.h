// Wavefront OBJ meshes as Mitsuba scenes reference them: positions, texture coordinates and
// faces (triangles, or polygons split into a fan as Mitsuba does). Normals, groups and
// materials of the file are not read (Glint shades quads with their geometric normal).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace glint {

struct ObjMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> uvs;   // one per position when the file gives them, else empty
  std::vector<int> triangles;   // 3 position indices per triangle, from 0
  bool has_normals = false;     // the file gives vertex normals
};

// Parses the text; throws ProjectError(file_label, "line N", problem) for a malformed line, an
// index out of range, or a vertex whose uv differs between faces (Glint's quads have one uv per
// corner).
ObjMesh parse_obj(const std::string& text, const std::string& file_label);

}  // namespace glint
