#include "renderer/scene.h"

#include "renderer/material_types.h"

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
  const auto index = static_cast<size_t>(type);
  return index < kMaterialTypeCount ? kMaterialTypes[index].name : "matte";
}

const char* to_string(Tonemap tonemap) {
  return tonemap == Tonemap::linear ? "linear" : "filmic";
}

std::optional<MaterialType> material_type_from_string(const std::string& text) {
  for (const MaterialTypeInfo& t : kMaterialTypes)
    if (text == t.name) return t.type;
  return std::nullopt;
}

std::optional<Tonemap> tonemap_from_string(const std::string& text) {
  if (text == "filmic") return Tonemap::filmic;
  if (text == "linear") return Tonemap::linear;
  return std::nullopt;
}

}  // namespace glint
