// The uniforms of a trace pass that describe the scene and the options (shaders/
// trace_common.glsl), kept apart from the programs: the generic program and each specialised one
// get them before every pass, since programs do not share uniform state.
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "renderer/mnee_casters.h"
#include "renderer/render_options.h"
#include "renderer/scene.h"

namespace glint {

class GlProgram;

struct TraceUniforms {
  glm::vec3 env_color{0};
  int env_textured = 0;
  float env_rotation = 0;
  int max_bounces = 0;
  int light_count = 0;
  float env_select = 0;
  glm::ivec2 env_distribution_size{1, 1};  // set by the environment's upload
  int russian_roulette = 0;
  float clamp = 0;
  int transparent_background = 0;
  int restart_together = 0;
  int sobol = 0;
  unsigned seed = 0;
  unsigned first_sample = 0;
  int sphere_count = 0;  // set by the geometry's upload, as quad_count
  int quad_count = 0;
  int caster_count = 0;  // set by the geometry's upload, as casters (renderer/mnee_casters.h)
  std::array<int, kMaxMneeCasters> casters{};
  int mnee_lights = 0;   // the lights MNEE samples (mnee_lights: kMneeLamps, kMneeEnvironment)
  int use_bvh = 0;
  int bvh_max_steps = 0;
  glm::vec3 cam_origin{0}, cam_right{0}, cam_up{0}, cam_forward{0};
  float cam_tan_half_vfov = 0, cam_aspect = 1, cam_aperture = 0, cam_focus = 1;
};

// What the frame's uniforms depend on besides the scene and the options.
struct FrameInputs {
  int light_count = 0;    // emitters in the light table
  bool use_bvh = false;   // closest hits with the BVH (else the loop over every shape)
  bool llvmpipe = false;  // the context is Mesa's llvmpipe (its loop limit applies)
  glm::dvec3 origin{0};   // render_origin of the packed scene
  int width = 0;          // of the film (the camera's aspect ratio)
  int height = 0;
  bool mnee = false;      // the program has manifold next-event estimation (more loops a sample)
};

// Sets every uniform of `u` but the counts and the environment tables' size, which the uploads
// set: camera (relative to the render origin), environment, bounces, light and environment
// sampling, roulette, clamp, path restart, sampler, seed, traversal.
void set_frame_uniforms(TraceUniforms& u, const Scene& scene, const RenderOptions& options,
                        const FrameInputs& in);

// How passes are split into draws (renderer/loop_budget.h) for `shapes` shapes.
struct DrawSplit {
  int samples_per_draw = 1;          // samples one draw adds per pixel
  bool exceeds_loop_limit = false;  // one sample may run more loop iterations than llvmpipe allows
};
DrawSplit draw_split(long shapes, int max_bounces, bool use_bvh);

// Sets the uniforms of `u` on `p` (a score of glProgramUniform calls: nothing next to a pass).
void apply_trace_uniforms(GlProgram& p, const TraceUniforms& u);

}  // namespace glint
