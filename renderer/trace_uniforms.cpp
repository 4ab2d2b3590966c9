#include "renderer/trace_uniforms.h"

#include <string>

#include "renderer/bvh.h"
#include "renderer/camera_frame.h"
#include "renderer/gl_program.h"
#include "renderer/loop_budget.h"
#include "renderer/path_restart.h"

namespace glint {

void set_frame_uniforms(TraceUniforms& u, const Scene& scene, const RenderOptions& options,
                        const FrameInputs& in) {
  const Environment& env = scene.environment;
  const bool textured = !env.texture.empty();
  u.env_color = textured ? glm::vec3(env.intensity) : env.color * env.intensity;
  u.env_textured = textured ? 1 : 0;
  u.env_rotation = glm::radians(env.rotation_deg);
  u.max_bounces = scene.render.max_bounces;
  u.use_bvh = in.use_bvh ? 1 : 0;
  // The step cap matters on llvmpipe only (its loop limit); elsewhere it is a generous bound
  // that only a pathological tree would reach. Draws are split the same way everywhere.
  u.bvh_max_steps = in.llvmpipe ? bvh_max_steps(kBvhMaxLeafSize, loop_budget_bounces(scene.render.max_bounces, in.mnee)) : kMaxBvhSteps;
  u.light_count = options.light_sampling ? in.light_count : 0;
  // Shadow rays go to an environment map (importance-sampled) half of the time when there are
  // also emitting shapes; a constant environment is left to BSDF sampling (cosine-weighted
  // sampling of a constant is already as good as it gets for matte surfaces).
  const bool env_lights = options.environment_sampling && textured && env.intensity > 0;
  u.env_select = env_lights ? (u.light_count > 0 ? 0.5f : 1.0f) : 0.0f;
  u.russian_roulette = options.russian_roulette ? 1 : 0;
  u.clamp = options.clamp;
  u.transparent_background = options.transparent_background ? 1 : 0;
  u.restart_together = restart_paths_together(options.restart, env) ? 1 : 0;
  u.sobol = options.sampler == SamplerKind::sobol ? 1 : 0;
  u.seed = static_cast<unsigned>(scene.render.seed);
  u.first_sample = options.first_sample;
  const float aspect = in.height > 0 ? static_cast<float>(in.width) / static_cast<float>(in.height) : 1.0f;
  const gpu::CameraFrame cam = make_camera_frame(scene.camera, aspect);
  u.cam_origin = glm::vec3(glm::dvec3(scene.camera.position) - in.origin);
  u.cam_right = cam.right;
  u.cam_up = cam.up;
  u.cam_forward = cam.forward;
  u.cam_tan_half_vfov = cam.tan_half_vfov;
  u.cam_aspect = cam.aspect;
  u.cam_aperture = cam.aperture;
  u.cam_focus = cam.focus;
}

DrawSplit draw_split(long shapes, int max_bounces, bool use_bvh) {
  const long per_sample =
      use_bvh ? bvh_loop_iterations_per_sample(bvh_max_steps(kBvhMaxLeafSize, max_bounces), kBvhMaxLeafSize,
                                               max_bounces)
              : loop_iterations_per_sample(shapes, max_bounces);
  return {samples_per_draw_for(per_sample), per_sample > kLlvmpipeLoopLimit};
}

void apply_trace_uniforms(GlProgram& p, const TraceUniforms& u) {
  p.set("u_env_color", u.env_color);
  p.set("u_env_textured", u.env_textured);
  p.set("u_env_rotation", u.env_rotation);
  p.set("u_max_bounces", u.max_bounces);
  p.set("u_light_count", u.light_count);
  p.set("u_env_select", u.env_select);
  p.set("u_env_distribution_size", u.env_distribution_size);
  p.set("u_russian_roulette", u.russian_roulette);
  p.set("u_clamp", u.clamp);
  p.set("u_transparent_background", u.transparent_background);
  p.set("u_restart_together", u.restart_together);
  p.set("u_sobol", u.sobol);
  p.set("u_seed", u.seed);
  p.set("u_first_sample", u.first_sample);
  p.set("u_sphere_count", u.sphere_count);
  p.set("u_quad_count", u.quad_count);
  p.set("u_caster_count", u.caster_count);
  p.set("u_mnee_lights", u.mnee_lights);
  for (int k = 0; k < u.caster_count; ++k)
    p.set(("u_casters[" + std::to_string(k) + "]").c_str(), u.casters[static_cast<size_t>(k)]);
  p.set("u_use_bvh", u.use_bvh);
  p.set("u_bvh_max_steps", u.bvh_max_steps);
  p.set("u_cam_origin", u.cam_origin);
  p.set("u_cam_right", u.cam_right);
  p.set("u_cam_up", u.cam_up);
  p.set("u_cam_forward", u.cam_forward);
  p.set("u_cam_tan_half_vfov", u.cam_tan_half_vfov);
  p.set("u_cam_aspect", u.cam_aspect);
  p.set("u_cam_aperture", u.cam_aperture);
  p.set("u_cam_focus", u.cam_focus);
}

}  // namespace glint
