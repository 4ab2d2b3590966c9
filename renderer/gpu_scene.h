// The scene packed into the std430 layouts of shaders/trace.frag (CPU side, no GL), and the
// assignment of texture-array layers. One layer per (texture, encoding) pair in use: a texture
// used both as colour (sRGB) and as roughness (linear) is decoded twice.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "renderer/image.h"
#include "renderer/scene.h"

namespace glint {

struct GpuSphere {
  glm::vec4 center_radius;
  glm::ivec4 material;
};

struct GpuQuad {
  glm::vec4 p0, p1, p2, p3;
  glm::vec4 uv01, uv23;
  glm::vec4 normal;
  glm::ivec4 material;
};

struct GpuMaterial {
  glm::vec4 color;     // rgb, a: type (the shader's MATERIAL_* constants)
  glm::vec4 emission;  // rgb
  glm::vec4 params;    // roughness, ior, opacity
  glm::ivec4 layers;   // colour, emission, roughness layer or -1
};

struct TextureLayer {
  int texture = -1;  // index into scene.textures
  ColorEncoding encoding = ColorEncoding::srgb;
  bool operator==(const TextureLayer&) const = default;
};

struct PackedScene {
  std::vector<GpuSphere> spheres;
  std::vector<GpuQuad> quads;
  std::vector<GpuMaterial> materials;
  std::vector<TextureLayer> layers;
};

// Assumes a validated scene (references resolve).
PackedScene pack_scene(const Scene& scene);

}  // namespace glint
