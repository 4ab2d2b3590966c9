// The scene tables of the trace program: the std430 structs of renderer/gpu_scene.h, the
// samplers in their fixed slot order, and the accessors of one table element.
// GLSL only, part of the trace program (shaders/trace_common.glsl includes it after the
// shared maths); not compiled as C++ (renderer/shader_lib.h), since it reads the uniforms,
// tables and samplers of the trace program.

struct GpuSphere {
  vec4 center_radius;
  ivec4 material;  // x: material index
};
struct GpuQuad {
  vec4 p0;
  vec4 p1;
  vec4 p2;
  vec4 p3;
  vec4 uv01;       // uv0.xy, uv1.xy
  vec4 uv23;       // uv2.xy, uv3.xy
  vec4 normal;     // xyz: geometric normal
  ivec4 material;  // x: material index
};
struct GpuMaterial {
  vec4 color;     // rgb colour, a: type
  vec4 emission;  // rgb
  vec4 params;    // roughness, ior, opacity
  ivec4 layers;   // texture layers of colour, emission, roughness; -1 for none
};

struct GpuLight {
  ivec4 shape;   // x: 0 sphere, 1 quad; y: its index; z: 1 for a parallelogram quad
  vec4 select;   // x: pdf of picking it, y: cdf, z: a quad's area
};

// The samplers, in a fixed order: each is given the next sampler slot in declaration order
// (after the entry point's own), and every one is read in every program (every_sampler, behind a
// uniform that is never set), so that a slot holds the same sampler in every specialised
// program. The reason is llvmpipe: it keys a compiled shader by the sampler state in each slot
// it reads, and Mesa leaves a buffer texture's slot as the last draw of any program set it. The
// buffer textures come last, on slots that no 2-D sampler of any program takes, so that their
// state is the same in the editor's context and in the worker's (program_worker.h), and the
// worker's warm-up draw compiles what the editor's first draw needs.
layout(binding = 2) uniform sampler2D u_environment;
// The textures' texels, row after row (lib/mapping.glsl's texel_index is the position).
layout(binding = 1) uniform sampler2D u_texels_8bit;   // RGBA8, as stored
layout(binding = 4) uniform sampler2D u_texels_float;  // RGBA32F
const int TEXEL_ROW_SHIFT = 14;  // 16384 texels a row (GpuRenderer::kTexelRowWidth)
ivec2 texel_position(int texel) {
  return ivec2(texel & ((1 << TEXEL_ROW_SHIFT) - 1), texel >> TEXEL_ROW_SHIFT);
}

// The scene's tables (renderer/gpu_scene.h, renderer/bvh.h, renderer/environment_distribution.h):
// their std430 bytes in integer buffer textures (RGBA32I, 16 bytes a texel, or R32I for the
// lists of ints and floats; a float is intBitsToFloat of its texel, every bit kept); texture
// unit 7 + k holds the renderer's table k (GpuRenderer::upload_table). Why not storage buffers:
// on llvmpipe a storage-buffer read is a loop over the SIMD group's lanes with a branch per lane
// and component, a texel fetch one gather, and a buffer texture's fetch is cheaper than a 2-D
// texture's (bench/reports/THROUGHPUT.md).
layout(binding = 7) uniform isamplerBuffer u_sphere_table;          // GpuSphere: 2 texels
layout(binding = 8) uniform isamplerBuffer u_quad_table;            // GpuQuad: 8 texels
layout(binding = 9) uniform isamplerBuffer u_material_table;        // GpuMaterial: 4 texels
layout(binding = 10) uniform isamplerBuffer u_texture_layer_table;  // ivec4, see lib/mapping.glsl
layout(binding = 11) uniform isamplerBuffer u_light_table;          // GpuLight: 2 texels
layout(binding = 12) uniform isamplerBuffer u_env_cdf_table;        // float (R32I)
layout(binding = 13) uniform isamplerBuffer u_bvh_node_table;       // BvhNode: 2 texels
layout(binding = 14) uniform isamplerBuffer u_bvh_primitive_table;  // int (R32I)

ivec4 table_texel(isamplerBuffer table, int texel) { return texelFetch(table, texel); }
vec4 table_vec4(isamplerBuffer table, int texel) {
  return intBitsToFloat(table_texel(table, texel));
}

// Never set (false): its only use is that every sampler above is read in every program.
uniform bool u_read_every_sampler;
vec4 every_sampler() {
  return texelFetch(u_environment, ivec2(0), 0) + texelFetch(u_texels_8bit, ivec2(0), 0) +
         texelFetch(u_texels_float, ivec2(0), 0) +
         vec4(texelFetch(u_sphere_table, 0) + texelFetch(u_quad_table, 0) +
              texelFetch(u_material_table, 0) + texelFetch(u_texture_layer_table, 0) +
              texelFetch(u_light_table, 0) + texelFetch(u_env_cdf_table, 0) +
              texelFetch(u_bvh_node_table, 0) + texelFetch(u_bvh_primitive_table, 0));
}
// Element i of a table; the compiler drops the fetches of fields that are not used.
GpuSphere sphere_at(int i) {
  return GpuSphere(table_vec4(u_sphere_table, 2 * i), table_texel(u_sphere_table, 2 * i + 1));
}
GpuQuad quad_at(int i) {
  int k = 8 * i;
  return GpuQuad(table_vec4(u_quad_table, k), table_vec4(u_quad_table, k + 1),
                 table_vec4(u_quad_table, k + 2), table_vec4(u_quad_table, k + 3),
                 table_vec4(u_quad_table, k + 4), table_vec4(u_quad_table, k + 5),
                 table_vec4(u_quad_table, k + 6), table_texel(u_quad_table, k + 7));
}
GpuMaterial material_at(int i) {
  int k = 4 * i;
  return GpuMaterial(table_vec4(u_material_table, k), table_vec4(u_material_table, k + 1),
                     table_vec4(u_material_table, k + 2), table_texel(u_material_table, k + 3));
}
GpuLight light_at(int i) {
  return GpuLight(table_texel(u_light_table, 2 * i), table_vec4(u_light_table, 2 * i + 1));
}
