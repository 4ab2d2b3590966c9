// The scene model of docs/DESIGN.md §6: plain values, no behaviour beyond small look-ups.
// Field defaults are the defaults of the project file format (missing keys take these).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace glint {

// The rows of renderer/material_types.h, in this order (their index is the shader's code).
enum class MaterialType { matte, reflective, glossy, transparent, refractive };
constexpr MaterialType kLastMaterialType = MaterialType::refractive;
enum class Tonemap { filmic, linear };

struct Camera {
  glm::vec3 position{0, 1, 5};
  glm::vec3 target{0, 0.5f, 0};
  glm::vec3 up{0, 1, 0};
  float vfov_deg = 40;
  float aperture_radius = 0;  // thin-lens radius in world units; 0 is a pinhole
  float focus_distance = 5;   // along the view direction

  bool operator==(const Camera&) const = default;
};

struct Film {
  int width = 960;
  int height = 540;

  bool operator==(const Film&) const = default;
};

struct RenderSettings {
  int max_bounces = 8;  // scattering events on a path; light found after the last still counts
  uint32_t seed = 0;    // selects an independent sample sequence

  bool operator==(const RenderSettings&) const = default;
};

struct DisplaySettings {
  float exposure = 0;  // stops
  Tonemap tonemap = Tonemap::filmic;

  bool operator==(const DisplaySettings&) const = default;
};

struct Environment {
  glm::vec3 color{0.5f, 0.5f, 0.5f};
  std::string texture;  // lat-long HDR/EXR path relative to the project; empty means none (null)
  float intensity = 1;
  float rotation_deg = 0;  // about +Y

  bool operator==(const Environment&) const = default;
};

struct Texture {
  std::string name;
  std::string path;  // relative to the project file (or absolute)

  bool operator==(const Texture&) const = default;
};

struct Material {
  std::string name;
  MaterialType type = MaterialType::matte;
  glm::vec3 color{0.8f, 0.8f, 0.8f};
  std::string color_texture;  // texture name; empty means none (null)
  glm::vec3 emission{0, 0, 0};
  std::string emission_texture;
  float roughness = 0;
  std::string roughness_texture;
  float ior = 1.5f;
  float opacity = 1;

  bool operator==(const Material&) const = default;
};

struct Sphere {
  std::string name;
  glm::vec3 center{0, 0, 0};
  float radius = 1;
  std::string material;

  bool operator==(const Sphere&) const = default;
};

// Two triangles (p0, p1, p2) and (p1, p3, p2); p3 is opposite p0.
struct Quad {
  std::string name;
  std::string material;
  std::array<glm::vec3, 4> corners{};
  std::array<glm::vec2, 4> uvs{glm::vec2{0, 0}, glm::vec2{0, 1}, glm::vec2{1, 0}, glm::vec2{1, 1}};

  bool operator==(const Quad&) const = default;
};

// A named camera bookmark (the editor's camera views): saved in the project, never rendered.
struct CameraView {
  std::string name;
  Camera camera;

  bool operator==(const CameraView&) const = default;
};

struct Scene {
  Camera camera;
  Film film;
  RenderSettings render;
  DisplaySettings display;
  Environment environment;
  std::vector<Texture> textures;
  std::vector<Material> materials;
  std::vector<Sphere> spheres;
  std::vector<Quad> quads;
  std::vector<CameraView> views;  // in no digest: bookmarks never reset the render

  // Not part of the file: the folder that relative asset paths are resolved against
  // (the project file's folder; the current folder for a scene that was never saved).
  std::filesystem::path base_dir;

  // Equal scenes render alike and save alike (base_dir included: it resolves the paths).
  bool operator==(const Scene&) const = default;
};

// Index look-ups by name; -1 when absent.
int find_material(const Scene& scene, const std::string& name);
int find_texture(const Scene& scene, const std::string& name);

// An asset path resolved against scene.base_dir (absolute paths are kept).
std::filesystem::path resolve_asset_path(const Scene& scene, const std::string& path);

const char* to_string(MaterialType type);
const char* to_string(Tonemap tonemap);
std::optional<MaterialType> material_type_from_string(const std::string& text);
std::optional<Tonemap> tonemap_from_string(const std::string& text);

}  // namespace glint
