#include "renderer/shader_features.h"

#include <algorithm>
#include <vector>

#include "renderer/image.h"
#include "renderer/material_types.h"
#include "renderer/loop_shapes.h"
#include "renderer/mnee_casters.h"
#include "renderer/quad_shape.h"

namespace glint {
namespace {

// Materials referenced by primitives; an unresolved name falls back to material 0 as in
// pack_scene (validated scenes have none).
std::vector<const Material*> used_materials(const Scene& scene) {
  std::vector<bool> used(scene.materials.size(), false);
  auto mark = [&](const std::string& name) {
    if (scene.materials.empty()) return;
    used[static_cast<size_t>(std::max(find_material(scene, name), 0))] = true;
  };
  for (const Sphere& s : scene.spheres) mark(s.material);
  for (const Quad& q : scene.quads) mark(q.material);
  std::vector<const Material*> out;
  for (size_t i = 0; i < used.size(); ++i)
    if (used[i]) out.push_back(&scene.materials[i]);
  return out;
}

bool texture_has_alpha(const Scene& scene, const std::string& texture_name) {
  int t = find_texture(scene, texture_name);
  if (t < 0) return true;
  try {
    ImageInfo info = probe_image(resolve_asset_path(scene, scene.textures[static_cast<size_t>(t)].path));
    return info.channels == 2 || info.channels >= 4;  // grey+alpha or RGBA
  } catch (const ImageError&) {
    return true;  // unknown: keep the coverage test
  }
}

}  // namespace

ShaderFeatures generic_features() { return ShaderFeatures{}; }

ShaderFeatures scene_features(const Scene& scene) {
  ShaderFeatures f;
  f.has_emitters = f.has_textures = f.has_coverage = false;
  f.material_types = 0;
  for (const Material* m : used_materials(scene)) {
    f.material_types |= 1u << static_cast<int>(m->type);
    // Emission is emission * texture: with zero emission the texture adds nothing.
    if (m->emission != glm::vec3(0)) f.has_emitters = true;
    if (!m->color_texture.empty() || !m->roughness_texture.empty() ||
        (!m->emission_texture.empty() && m->emission != glm::vec3(0)))
      f.has_textures = true;
    if (m->opacity < 1 || (!m->color_texture.empty() && texture_has_alpha(scene, m->color_texture)))
      f.has_coverage = true;
  }
  f.env_textured = !scene.environment.texture.empty();
  f.has_spheres = !scene.spheres.empty();
  f.has_quads = !scene.quads.empty();
  f.has_general_quads = std::any_of(scene.quads.begin(), scene.quads.end(),
                                    [](const Quad& q) { return !quad_is_planar_convex(q.corners); });
  f.has_general_quad_lights = std::any_of(scene.quads.begin(), scene.quads.end(), [&](const Quad& q) {
    const int m = std::max(find_material(scene, q.material), 0);
    const bool emits = !scene.materials.empty() &&
                       scene.materials[static_cast<size_t>(m)].emission != glm::vec3(0);
    return emits && !quad_is_parallelogram(q.corners);
  });
  f.thin_lens = scene.camera.aperture_radius > 0;
  f.mnee = scene_needs_mnee(scene);
  return f;
}

ShaderFeatures with_loop_counts(ShaderFeatures f, long spheres, long quads) {
  const bool fixed = f.loop_traversal && !f.bvh_traversal && unrolls_loop(spheres, quads);
  f.loop_spheres = fixed ? static_cast<int>(spheres) : -1;
  f.loop_quads = fixed ? static_cast<int>(quads) : -1;
  return f;
}

bool covers(const ShaderFeatures& program, const ShaderFeatures& needed) {
  auto ok = [](bool have, bool need) { return have || !need; };
  return ok(program.has_emitters, needed.has_emitters) &&
         ok(program.has_textures, needed.has_textures) &&
         ok(program.env_textured, needed.env_textured) && ok(program.thin_lens, needed.thin_lens) &&
         ok(program.has_coverage, needed.has_coverage) &&
         ok(program.has_spheres, needed.has_spheres) && ok(program.has_quads, needed.has_quads) &&
         ok(program.has_general_quads, needed.has_general_quads) &&
         ok(program.has_general_quad_lights, needed.has_general_quad_lights) &&
         ok(program.loop_traversal, needed.loop_traversal) &&
         ok(program.bvh_traversal, needed.bvh_traversal) &&
         ok(program.pcg_sampler, needed.pcg_sampler) && ok(program.sobol_sampler, needed.sobol_sampler) &&
         (needed.material_types & ~program.material_types) == 0 &&
         (program.loop_spheres < 0 || (program.loop_spheres == needed.loop_spheres &&
                                       program.loop_quads == needed.loop_quads));
}

std::string shader_defines(const ShaderFeatures& f) {
  std::string out;
  auto define = [&](bool present, const char* name) {
    if (!present) out += std::string("#define ") + name + "\n";
  };
  define(f.has_emitters, "GLINT_NO_EMITTERS");
  define(f.has_textures, "GLINT_NO_TEXTURES");
  define(f.env_textured, "GLINT_NO_ENV_TEXTURE");
  define(f.thin_lens, "GLINT_NO_THIN_LENS");
  define(f.has_coverage, "GLINT_NO_COVERAGE");
  for (const MaterialTypeInfo& t : kMaterialTypes) define(f.uses(t.type), t.omit_define);
  define(f.loop_traversal, "GLINT_NO_LOOP");
  define(f.bvh_traversal, "GLINT_NO_BVH");
  define(f.has_spheres, "GLINT_NO_SPHERES");
  define(f.has_quads, "GLINT_NO_QUADS");
  define(f.has_general_quads, "GLINT_NO_GENERAL_QUADS");
  define(f.has_general_quad_lights, "GLINT_NO_GENERAL_QUAD_LIGHTS");
  define(f.pcg_sampler, "GLINT_NO_PCG_SAMPLER");
  define(f.sobol_sampler, "GLINT_NO_SOBOL_SAMPLER");
  if (f.mnee) out += "#define GLINT_MNEE\n";
  if (f.loop_spheres >= 0) {
    out += "#define GLINT_LOOP_SPHERES " + std::to_string(f.loop_spheres) + "\n";
    out += "#define GLINT_LOOP_QUADS " + std::to_string(f.loop_quads) + "\n";
  }
  return out;
}

}  // namespace glint
