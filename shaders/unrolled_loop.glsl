// The closest hit in a program compiled for a scene of exactly GLINT_LOOP_SPHERES spheres and
// GLINT_LOOP_QUADS quads (renderer/shader_features.h: loop_spheres, loop_quads), each shape
// tested in turn like closest_hit_loop (lib/bvh.glsl), with the same result.
// Why: on llvmpipe a table fetch is a per-lane gather, since the loop index is not known to be
// the same in every lane; a uniform-block load at a constant offset is one scalar load for all
// lanes (gallivm's load_ubo takes that path only for an offset that nir_src_is_always_uniform
// proves, a constant). Mesa's NIR unrolls a loop that indexes a local array whose size is the
// loop's trip count (nir_loop_analyze.c, force_unroll_array_access), up to the driver's
// max_unroll_iterations (32 on llvmpipe). So each loop below copies the block's shapes into such
// an array; once unrolled, each test reads its shape from the block at a constant offset.
// Included by trace_common.glsl after GpuSphere, GpuQuad, sphere_hit and quad_hit.
#ifndef GLINT_UNROLLED_LOOP_GLSL
#define GLINT_UNROLLED_LOOP_GLSL

// The scene's first shapes, as the tables hold them (renderer/loop_shapes.h fills the block;
// std140 lays these structs of vec4s out as std430 does). The sizes are the block's, the
// same for every count: kLoopShapesMax in renderer/loop_shapes.h.
layout(std140, binding = 0) uniform LoopShapes {
  GpuSphere loop_spheres[32];
  GpuQuad loop_quads[32];
};

PrimitiveHit closest_hit_unrolled(Ray ray, float tmax) {
  PrimitiveHit best = PrimitiveHit(tmax, -1, 0, true);
#if GLINT_LOOP_SPHERES > 0
  vec4 spheres[GLINT_LOOP_SPHERES];
  for (int i = 0; i < GLINT_LOOP_SPHERES; ++i) spheres[i] = loop_spheres[i].center_radius;
  for (int i = 0; i < GLINT_LOOP_SPHERES; ++i) {
    float t = sphere_hit(spheres[i], ray, best.t);
    if (t != NO_HIT) {
      best.t = t;
      best.ref = i;
    }
  }
#endif
#if GLINT_LOOP_QUADS > 0
  GpuQuad quads[GLINT_LOOP_QUADS];
  for (int i = 0; i < GLINT_LOOP_QUADS; ++i) quads[i] = loop_quads[i];
  for (int i = 0; i < GLINT_LOOP_QUADS; ++i) {
    float t = quad_hit(quads[i], ray, best.t);
    if (t != NO_HIT) {
      best.t = t;
      best.ref = GLINT_LOOP_SPHERES + i;
    }
  }
#endif
  return best;
}

#endif
