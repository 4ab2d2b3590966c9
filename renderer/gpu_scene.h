// The scene packed into the std430 layouts of shaders/lib/trace_scene_tables.glsl (CPU side,
// no GL; the shader reads them from integer textures, 16 bytes a texel), and the
// assignment of texture layers. One layer per (texture, encoding) pair in use: a texture used
// both as colour (sRGB) and as roughness (linear) has two layers over the same texels.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "renderer/image.h"
#include "renderer/scene.h"

namespace glint {

struct GpuSphere {
  glm::vec4 center_radius;
  glm::ivec4 material;  // x: material index, y: light index or -1, z: 1 for an MNEE caster
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

// An emitting sphere or quad for next-event estimation. The shader picks one by binary search
// on `cdf` and needs `pdf` again when a BSDF-sampled ray hits the same shape (MIS).
struct GpuLight {
  glm::ivec4 shape;  // x: 0 sphere, 1 quad; y: index into spheres or quads; z: 1 for a
                     // parallelogram quad (quad_is_parallelogram), else 0
  glm::vec4 select;  // x: pdf of picking this light, y: cdf (exactly 1 for the last), z: a
                     // quad's area (with GpuQuad::normal, its pdf without the other corners)
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
  std::vector<GpuLight> lights;  // material.y of a sphere or quad is its light index, else -1
  std::vector<int> casters;      // spheres of manifold next-event estimation (mnee_casters)
};

// Estimated power of an emitter: luminance of `emission` times area (textures ignored: the
// estimate only steers which light a shadow ray goes to, any positive value is unbiased).
double emitter_power(const glm::vec3& emission, double area);

// Assumes a validated scene (references resolve). Positions are stored relative to `origin`
// (subtracted in double): camera-relative rendering, see render_origin.
PackedScene pack_scene(const Scene& scene, const glm::dvec3& origin = glm::dvec3(0));

// The world point the GPU's float coordinates are relative to. A float has 24 bits: a scene
// 1e5 from the world origin is only known to 0.008 there and rays must keep 16 epsilons of the
// coordinates (0.19) from surfaces, which shifts contact shadows and light edges. Relative to a
// point near the camera, what the camera sees is known to the precision of its own size. The
// point is the camera position snapped to a grid of 1/64 of its distance from the world origin
// (in powers of two), so orbiting the camera rarely moves it (moving it re-uploads the scene);
// within 1024 of the world origin it is the world origin itself.
glm::dvec3 render_origin(const glm::vec3& camera_position);

}  // namespace glint
