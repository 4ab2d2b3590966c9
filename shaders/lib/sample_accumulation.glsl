// The samples of a pass: adaptive sampling's choice of pixels, the start of a camera sample,
// and the running mean and variance (Kahan-compensated) that a pass adds its samples to.
// GLSL only, part of the trace program (shaders/trace_common.glsl includes it after the
// shared maths); not compiled as C++ (renderer/shader_lib.h), since it reads the uniforms,
// tables and samplers of the trace program.

// Whether adaptive sampling adds samples to this pixel in this pass. The allocation that
// minimises the image's summed error for a sample budget gives each pixel samples in proportion
// to its standard deviation (the Neyman allocation of stratified sampling, Cochran, "Sampling
// Techniques", 3rd ed., §5.5); at that optimum every pixel's error per sample, relMSE / n, is
// the same, so a pixel above the image's mean of it (u_adaptive_threshold, from the last
// estimate) needs samples and one below it waits, as Cycles' adaptive sampling lets converged
// pixels wait. Unlike Cycles none waits forever: every u_adaptive_every-th pass samples all, so
// each pixel's count grows without bound and the image stays consistent.
bool adaptive_pixel_active(vec4 accumulation, vec4 compensation, vec3 variance) {
  if (!u_adaptive) return true;
  float taken = compensation.a;
  if (taken < float(u_adaptive_min_samples) || u_pass_index % u_adaptive_every == 0u) return true;
  float finite = taken - accumulation.a;
  float r = estimated_pixel_relmse(accumulation.rgb, variance, finite);
  return r < 0.0 || r / finite >= u_adaptive_threshold;  // no estimate yet: sample
}

// Sets the per-sample random state of sample `index` (of the pixel's sequence, before
// u_first_sample) and returns its camera path.
PathState start_sample(CameraFrame cam, ivec2 pixel, uint index) {
  g_sample_index = u_first_sample + index;
  g_rng = rng_seed(uint(pixel.x), uint(pixel.y), g_sample_index, u_seed);
  // Without next-event estimation there is no first light point to pair the pixel position
  // with: the pixel takes a 2-D point (Sobol dimensions 0 and 1, a (0,2)-sequence) and the 4-D
  // point's two costlier dimensions are not computed.
  if (u_sobol) {
    g_primary = light_sampling_on() ? sobol_sample_4d(g_sample_index, g_pixel_seed, 0u)
                                    : vec4(0.0, 0.0, sobol_sample_2d(g_sample_index, g_pixel_seed, 0u));
  }
  g_incomplete = false;
  g_primary_escaped = false;
  vec2 jitter = sample_2d(0u);
  vec2 film = (vec2(float(pixel.x), float(pixel.y)) + jitter) / vec2(u_resolution);
  vec2 lens = sample_2d(1u);
  return start_path(camera_ray(cam, film, lens));
}

// Adds u_samples_per_pass samples to the pixel's running mean and variance: `accumulation`
// (rgb the mean, a the discarded count), `compensation` (what float32 could not hold of the
// mean; a the samples taken), `variance` and `variance_compensation` (the same for the mean
// squared deviation) hold the pixel's state before the pass (zero before the first) and
// receive it after; `covered` counts the finite samples whose camera ray hit a surface. The
// two entry points (trace.frag, trace.comp) differ only in where they read and write it. A
// pixel outside the region, or waiting with adaptive sampling, keeps its state.
bool in_sample_region(ivec2 pixel) {
  return !u_region_on || (all(greaterThanEqual(pixel, u_region.xy)) && all(lessThan(pixel, u_region.zw)));
}

void add_samples(ivec2 pixel, inout vec4 accumulation, inout vec4 compensation,
                 inout vec3 variance, inout vec3 variance_compensation, inout float covered) {
  if (u_read_every_sampler) accumulation += every_sampler();
  if (!in_sample_region(pixel)) return;
  if (!adaptive_pixel_active(accumulation, compensation, variance)) return;
  CameraFrame cam = CameraFrame(u_cam_origin, u_cam_right, u_cam_up, u_cam_forward,
                                u_cam_tan_half_vfov, u_cam_aspect, u_cam_aperture, u_cam_focus);
  uint row = uint(pixel.y);
  vec4 previous = accumulation;
  // Without adaptive sampling every pixel has taken u_samples_before samples; with it, its own
  // count, so that its sample indices (and its Sobol' points) continue without a gap.
  uint samples_before = u_adaptive || u_per_pixel_counts ? uint(compensation.a) : u_samples_before;
  // The pass adds the sum of the samples' deviations from the previous mean, not their sum:
  // mean += sum(l - mean) / n. The deviations are small (exactly 0 for a constant once the mean
  // has reached it), so their rounding is small too; summing the samples themselves and
  // subtracting k * mean rounds both terms at the size of k * mean, and that error, divided by
  // n each pass, drifted a constant by 1e-5 (relative) over 1000 passes of 1000 samples
  // (hard_Accumulation.MillionSamplesOfAConstantDoNotDrift).
  g_pixel_seed = sobol_pixel_seed(uint(pixel.x), row, u_seed);
  vec3 deviation_sum = vec3(0.0);
  // The variance's sums are taken about `shift`: the previous mean, or for a pixel's first
  // finite sample that sample itself (about 0, sum(l^2) - sum(l)^2 / k would cancel to a
  // rounding error of the size of l^2 for a constant l).
  bool no_mean_yet = float(samples_before) - previous.a <= 0.0;
  vec3 shift = previous.rgb;
  vec3 shifted_sum = vec3(0.0);
  vec3 shifted_square_sum = vec3(0.0);
  int finite_count = 0;
  int covered_count = 0;
  // Path regeneration: one loop over the pass's bounces, in which a lane whose path has ended
  // starts its next sample. A SIMD group (8 lanes on llvmpipe) runs each iteration while any
  // lane is active, so with a loop per sample every sample would cost the longest path of the
  // group. Starting at once keeps lanes busy where paths differ much in length (closed rooms);
  // where they are short and alike (open scenes) starting together pays the start-up code once
  // per group and keeps the group's rays coherent (u_restart_together; bench/reports/THROUGHPUT.md).
  // Each sample is the same (its random numbers, its arithmetic) as when traced alone, and the
  // samples are added in order, so the image does not depend on the policy.
  // The loop's own condition ends it, not a `break` alone: Mesa 25's llvmpipe never ended a
  // `for (;;)` left only by a `break` in this fragment shader (the same loop in the compute
  // shader ended).
  int s = 0;
  PathState path = start_sample(cam, pixel, samples_before);
  bool in_flight = true;
  while (s < u_samples_per_pass) {
    if (in_flight) in_flight = continue_path(path);
    // Every lane still in the loop votes, so that the vote sees the whole active group.
#if defined(GLINT_GROUP_VOTE)
    bool group_idle = allInvocationsARB(!in_flight);
#else
    bool group_idle = true;
#endif
    if (in_flight || (u_restart_together && !group_idle)) continue;
    vec3 l = path.radiance;
    // The firefly clamp scales a sample down to luminance u_clamp: biased, off by default.
    float lum = luminance(l);
    if (u_clamp > 0.0 && lum > u_clamp) l *= u_clamp / lum;
    if (is_finite(l) && !g_incomplete) {
      deviation_sum += l - previous.rgb;
      if (no_mean_yet && finite_count == 0) shift = l;
      shifted_sum += l - shift;
      shifted_square_sum += (l - shift) * (l - shift);
      ++finite_count;
      if (!g_primary_escaped) ++covered_count;
    }
    if (++s < u_samples_per_pass) {
      path = start_sample(cam, pixel, samples_before + uint(s));
      in_flight = true;
    }
  }
  float discarded = previous.a + float(u_samples_per_pass - finite_count);
  float taken = float(samples_before) + float(u_samples_per_pass);
  float finite_total = taken - discarded;
  // The increment sum(l - mean) / n itself is rounded when added to the mean: by up to half an
  // ulp of the mean, and when most increments are smaller than that (a pixel of a constant
  // background with a rare brighter sample, late in a long run) they round the same way every
  // time. Plain float32 then drifted such a pixel by 0.1% over 10^5 one-sample passes
  // (tests/soak, bench/reports/SOAK.md). Kahan's compensated summation (Higham, "Accuracy and
  // Stability of Numerical Algorithms", 2nd ed., §4.3) keeps what each addition lost in
  // `compensation` and adds it back the next time: the represented mean is mean - compensation
  // (so the deviations, taken from `mean`, are short by finite_count * compensation).
  // `precise` forbids the compiler to simplify (t - mean) - y to 0.
  precise vec3 mean = previous.rgb;
  precise vec3 lost = compensation.rgb;
  if (finite_total > 0.0) {
    precise vec3 y = (deviation_sum + float(finite_count) * lost) / finite_total - lost;
    precise vec3 t = mean + y;
    lost = (t - mean) - y;
    mean = t;
  }
  // The variance, v = M2 / n, by Chan, Golub and LeVeque's pairwise update ("Algorithms for
  // computing the sample variance", 1983) of M2 with the pass's k samples, written with the
  // deviations d from the previous mean (from the first sample when there is none):
  // M2' = M2 + sum(d^2) - sum(d)^2 / n', so that v' = v + (sum(d^2) - sum(d)^2 / n' - k v) / n'.
  // Every term is a deviation, not a square of the radiance, so nothing cancels; the
  // increment is added with Kahan's compensation as the mean's is.
  precise vec3 v = variance;
  precise vec3 v_lost = variance_compensation;
  if (finite_total > 0.0) {
    vec3 m2_increment = max(shifted_square_sum - shifted_sum * shifted_sum / finite_total, vec3(0.0));
    precise vec3 y = (m2_increment - float(finite_count) * (v - v_lost)) / finite_total - v_lost;
    precise vec3 t = v + y;
    v_lost = (t - v) - y;
    v = t;
  }
  accumulation = vec4(mean, discarded);
  compensation = vec4(lost, taken);
  variance = v;
  variance_compensation = v_lost;
  covered += float(covered_count);
}
