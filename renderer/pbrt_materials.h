// pbrt-v4 materials -> Glint materials for pbrt_reader.cpp: the inverse of pbrt_writer.cpp's
// choices (roughness as alpha, remapped or not), and the nearest Glint type, with a warning,
// for the others.
#pragma once

#include <functional>
#include <map>
#include <string>

#include "renderer/pbrt_tokens.h"
#include "renderer/scene.h"

namespace glint::pbrt {

struct MaterialReader {
  Scene& scene;
  const std::map<std::string, std::string>& image_textures;  // pbrt texture name -> image file
  std::function<void(const std::string&)> warn;

  // Appends the material of pbrt's `type` and parameters to scene.materials under `name` (made
  // unique: "name-2") and returns that name. Parameters it reads are marked used.
  std::string read(const std::string& name, const std::string& type, const Params& ps);

 private:
  std::string glint_texture(const std::string& name);
  float roughness(const Params& ps);
  glm::vec3 colour(const Params& ps, const std::string& name, glm::vec3 fallback, Material& m);
};

}  // namespace glint::pbrt
