// Which parts of the trace shader a scene needs ("model only what a scene needs").
// Each feature that is absent becomes a `#define GLINT_NO_...` line after `#version` of
// shaders/trace.frag and trace.comp; a macro that is not defined means the feature is present, so the C++
// build of the shader library (renderer/shader_lib.h), which defines none, keeps every branch.
// A scene of few shapes also fixes their numbers (loop_spheres, loop_quads): a program compiled
// for them unrolls the closest-hit loop.
// Only features whose removal makes the shader cheaper are listed; removing one never changes
// the random-number sequence, so generic and specialised programs render the same image.
// On Mesa's llvmpipe the shader runs as SIMD vectors of pixels and an `if` masks lanes: Mesa
// 22 runs both sides of every `if` (only loops branch), so a branch that no pixel takes still
// costs its full time; Mesa 25 skips a side that no lane of the group takes, but runs both
// where the group's lanes disagree, as they do wherever its pixels see different materials.
// So code that a uniform switches off is compiled out wherever the scene allows it
// (bench/reports/THROUGHPUT.md measures it on both).
#pragma once

#include <cstdint>
#include <string>

#include "renderer/scene.h"

namespace glint {

struct ShaderFeatures {
  bool has_emitters = true;   // a used material has non-zero emission
  bool has_textures = true;   // a used material references a texture (any slot)
  bool env_textured = true;   // the environment is an image
  bool thin_lens = true;      // aperture_radius > 0
  bool has_coverage = true;   // a used material has opacity < 1 or a colour texture with alpha
  bool has_spheres = true;    // the scene has a sphere
  bool has_quads = true;      // the scene has a quad
  // A quad that is not planar and convex (renderer/quad_shape.h): without one, quads are tested
  // by the cheaper intersect_planar_quad instead of as two triangles.
  bool has_general_quads = true;
  // An emitting quad that is not a parallelogram (renderer/quad_shape.h): without one, every
  // quad light is sampled by sample_parallelogram_light and the two-triangle sampler is left out.
  bool has_general_quad_lights = true;
  uint32_t material_types = 0x1F;  // bit (1 << int(MaterialType)) per type used by a primitive
  // Closest hits by the loop over all shapes, by the BVH (shaders/lib/bvh.glsl). The scene alone
  // does not decide (the render options may force one): scene_features keeps both, and the
  // renderer keeps the one it uses (renderer/bvh.h, use_bvh). With both, u_use_bvh chooses.
  bool loop_traversal = true;
  bool bvh_traversal = true;
  // The sampler of the render options (RenderOptions::sampler), kept like the traversals: the
  // scene keeps both, the renderer the one it uses; with one, u_sobol is a constant.
  bool pcg_sampler = true;
  bool sobol_sampler = true;
  // A program for exactly this many spheres and quads, whose closest-hit loop is unrolled and
  // reads the shapes from a uniform block (renderer/loop_shapes.h); -1: any number, read from the
  // tables. Set by with_loop_counts, for scenes that the loop traverses; the two go together.
  int loop_spheres = -1;
  int loop_quads = -1;
  // Manifold next-event estimation of caustics through smooth spheres (shaders/lib/
  // manifold_nee.glsl, `#define GLINT_MNEE`), for scenes that scene_needs_mnee
  // (renderer/mnee_casters.h). Unlike the others it adds a strategy rather than code for a
  // present feature: absent from the generic program, and a program with or without it
  // renders any scene (each is unbiased), so `covers` ignores it.
  bool mnee = false;

  bool uses(MaterialType t) const { return (material_types >> static_cast<int>(t)) & 1u; }
  bool operator==(const ShaderFeatures&) const = default;
};

// Every feature present: the program compiled at start-up, right for any scene.
ShaderFeatures generic_features();

// What `scene` needs. "Used" means referenced by a sphere or a quad. A colour texture counts as
// having alpha when its file has an alpha channel (header probe) or cannot be probed.
ShaderFeatures scene_features(const Scene& scene);

// `f` with the counts of an unrolled loop when the scene of `spheres` and `quads` is traced by the
// loop alone and unrolls_loop allows it (renderer/loop_shapes.h), else with both -1.
ShaderFeatures with_loop_counts(ShaderFeatures f, long spheres, long quads);

// True when a program compiled for `program` renders every scene that needs `needed`.
bool covers(const ShaderFeatures& program, const ShaderFeatures& needed);

// `#define GLINT_NO_...` lines (each ending in '\n') for the absent features, and
// `#define GLINT_LOOP_SPHERES n` and `GLINT_LOOP_QUADS m` for an unrolled loop; empty for
// generic_features(). Also serves as the key of the program cache.
std::string shader_defines(const ShaderFeatures& features);

}  // namespace glint
