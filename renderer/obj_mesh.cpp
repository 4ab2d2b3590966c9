#include "renderer/obj_mesh.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "renderer/project_error.h"

namespace glint {

namespace {

[[noreturn]] void fail(const std::string& file, int line, const std::string& problem) {
  throw ProjectError(file, "line " + std::to_string(line), problem);
}

float number(std::istringstream& in, const std::string& file, int line, const char* what) {
  std::string word;
  if (!(in >> word)) fail(file, line, std::string("expected ") + what);
  char* end = nullptr;
  const double v = std::strtod(word.c_str(), &end);
  if (end != word.c_str() + word.size() || !std::isfinite(v)) fail(file, line, std::string("expected ") + what + ", got '" + word.substr(0, 40) + "'");
  return static_cast<float>(v);
}

// One "v/vt/vn" corner: its position and uv indices from 0 (-1 for no uv). Negative OBJ
// indices count back from the last element read so far.
std::pair<int, int> corner(const std::string& word, size_t positions, size_t uvs, const std::string& file, int line) {
  int index[2] = {0, 0};
  size_t start = 0;
  for (int k = 0; k < 2 && start <= word.size(); ++k) {
    const size_t slash = word.find('/', start);
    const std::string part = word.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
    if (!part.empty()) {
      char* end = nullptr;
      const long v = std::strtol(part.c_str(), &end, 10);
      const size_t count = k == 0 ? positions : uvs;
      const long resolved = v < 0 ? long(count) + v + 1 : v;
      if (end != part.c_str() + part.size() || v == 0 || resolved < 1 || resolved > long(count))
        fail(file, line, "face corner '" + word.substr(0, 40) + "' names no " + (k == 0 ? "vertex" : "texture coordinate") + " read so far");
      index[k] = int(resolved);
    } else if (k == 0) {
      fail(file, line, "face corner '" + word.substr(0, 40) + "' has no vertex index");
    }
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return {index[0] - 1, index[1] - 1};
}

}  // namespace

ObjMesh parse_obj(const std::string& text, const std::string& file) {
  ObjMesh mesh;
  std::vector<glm::vec2> file_uvs;
  std::vector<int> uv_of;  // per position: the index in file_uvs, -1 unset
  std::istringstream lines(text);
  std::string row;
  int line = 0;
  while (std::getline(lines, row)) {
    ++line;
    std::istringstream in(row);
    std::string key;
    if (!(in >> key) || key[0] == '#') continue;
    if (key == "v") {
      glm::vec3 p;
      for (int k = 0; k < 3; ++k) p[k] = number(in, file, line, "a vertex coordinate");
      mesh.positions.push_back(p);
      uv_of.push_back(-1);
    } else if (key == "vt") {
      glm::vec2 uv;
      for (int k = 0; k < 2; ++k) uv[k] = number(in, file, line, "a texture coordinate");
      file_uvs.push_back(uv);
    } else if (key == "vn") {
      mesh.has_normals = true;
    } else if (key == "f") {
      std::vector<int> face;
      std::string word;
      while (in >> word) {
        const auto [p, t] = corner(word, mesh.positions.size(), file_uvs.size(), file, line);
        if (t >= 0) {
          if (uv_of[p] >= 0 && file_uvs[uv_of[p]] != file_uvs[t])
            fail(file, line, "vertex " + std::to_string(p + 1) + " has two different texture coordinates");
          uv_of[p] = t;
        }
        face.push_back(p);
      }
      if (face.size() < 3) fail(file, line, "a face needs at least 3 corners");
      for (size_t k = 1; k + 1 < face.size(); ++k)
        mesh.triangles.insert(mesh.triangles.end(), {face[0], face[k], face[k + 1]});
    } else if (key != "o" && key != "g" && key != "s" && key != "usemtl" && key != "mtllib") {
      fail(file, line, "unknown statement '" + key.substr(0, 20) + "'");
    }
  }
  bool any_uv = false;
  for (int t : uv_of) any_uv |= t >= 0;
  if (any_uv)
    for (int t : uv_of) mesh.uvs.push_back(t >= 0 ? file_uvs[t] : glm::vec2(0));
  return mesh;
}

}  // namespace glint
