#include "renderer/scene.h"

namespace glint {

int find_material(const Scene& scene, const std::string& name) {
  for (size_t i = 0; i < scene.materials.size(); ++i)
    if (scene.materials[i].name == name) return static_cast<int>(i);
  return -1;
}

int find_texture(const Scene& scene, const std::string& name) {
  for (size_t i = 0; i < scene.textures.size(); ++i)
    if (scene.textures[i].name == name) return static_cast<int>(i);
  return -1;
}

std::filesystem::path resolve_asset_path(const Scene& scene, const std::string& path) {
  std::filesystem::path p(path);
  if (p.is_absolute() || scene.base_dir.empty()) return p;
  return scene.base_dir / p;
}

const char* to_string(MaterialType type) {
  switch (type) {
    case MaterialType::matte: return "matte";
    case MaterialType::reflective: return "reflective";
    case MaterialType::glossy: return "glossy";
    case MaterialType::transparent: return "transparent";
    case MaterialType::refractive: return "refractive";
  }
  return "matte";
}

const char* to_string(Tonemap tonemap) {
  return tonemap == Tonemap::linear ? "linear" : "filmic";
}

std::optional<MaterialType> material_type_from_string(const std::string& text) {
  for (auto t : {MaterialType::matte, MaterialType::reflective, MaterialType::glossy,
                 MaterialType::transparent, MaterialType::refractive})
    if (text == to_string(t)) return t;
  return std::nullopt;
}

std::optional<Tonemap> tonemap_from_string(const std::string& text) {
  if (text == "filmic") return Tonemap::filmic;
  if (text == "linear") return Tonemap::linear;
  return std::nullopt;
}

}  // namespace glint
