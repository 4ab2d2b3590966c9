#include "tests/soak/soak.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <epoxy/gl.h>

#include "editor/viewport_renderer.h"
#include "renderer/gl_context.h"
#include "renderer/gpu_renderer.h"
#include "renderer/project_file.h"
#include "renderer/render_session.h"
#include "renderer/scene_validation.h"
#include "renderer/shader_lib.h"

namespace glint::soak {
namespace {

constexpr int kSettleFrames = 8;

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

// Region r of a pixel: 0 is the whole image, 1..4 the quadrants (top-left, top-right,
// bottom-left, bottom-right).
bool in_region(int r, int x, int y, int w, int h) {
  if (r == 0) return true;
  const bool right = 2 * x >= w, bottom = 2 * y >= h;
  return (r - 1) == (bottom ? 2 : 0) + (right ? 1 : 0);
}

// Region means of an accumulation read-back, in double.
std::vector<double> region_means(const Image& img) {
  std::vector<double> mean(kRegions, 0.0), count(kRegions, 0.0);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int r = 0; r < kRegions; ++r)
        if (in_region(r, x, y, img.width, img.height)) {
          mean[r] += luminance(img.at(x, y));
          count[r] += 1;
        }
  for (int r = 0; r < kRegions; ++r) mean[r] /= std::max(count[r], 1.0);
  return mean;
}

// Edit i of phase 1, as a user drags a slider or a gizmo: each kind in turn, each time to a
// value it did not have (so that every edit must restart the accumulation).
void apply_edit(Scene& s, const Scene& base, int64_t i) {
  const int64_t step = i / 6;
  const float t = static_cast<float>(step % 50 + 1) / 50.0f;  // in (0, 1]
  const bool odd = step % 2 == 1;
  const int material = !base.spheres.empty() ? find_material(base, base.spheres[0].material)
                       : !base.quads.empty() ? find_material(base, base.quads[0].material)
                                             : -1;
  switch (i % 6) {
    case 0:  // drag the first sphere (or quad) sideways
      if (!base.spheres.empty()) {
        s.spheres[0].center = base.spheres[0].center + glm::vec3(0.1f * t, 0, 0);
      } else if (!base.quads.empty()) {
        for (int c = 0; c < 4; ++c) s.quads[0].corners[c] = base.quads[0].corners[c] + glm::vec3(0.1f * t, 0, 0);
      }
      break;
    case 1:
      if (material >= 0) {  // towards its complement (a black material changes too)
        const glm::vec3 c = base.materials[material].color;
        s.materials[material].color = c + (glm::vec3(1) - 2.0f * c) * (0.5f * t);
      }
      break;
    case 2:
      if (material >= 0) s.materials[material].roughness = 0.5f * t;
      break;
    case 3:  // the type: a new set of shader features (a specialised program on first use)
      if (material >= 0) {
        const MaterialType other = base.materials[material].type == MaterialType::glossy ? MaterialType::matte
                                                                                         : MaterialType::glossy;
        s.materials[material].type = odd ? base.materials[material].type : other;
      }
      break;
    case 4:  // re-uploads the environment (and its sampling tables)
      s.environment.intensity = base.environment.intensity * (1.0f + 0.2f * t);
      break;
    case 5: {  // orbit the camera a little about its target
      const float a = 0.05f * t;
      glm::vec3 d = base.camera.position - base.camera.target;
      s.camera.position = base.camera.target +
                          glm::vec3(d.x * std::cos(a) - d.z * std::sin(a), d.y, d.x * std::sin(a) + d.z * std::cos(a));
      break;
    }
  }
}

float exposure_value(int64_t j) { return 0.25f * static_cast<float>(j % 9 - 4) + 0.125f; }

// Sums in double of batch means (per region), for their mean and spread.
struct BatchSums {
  double sum[kRegions] = {}, sum2[kRegions] = {};
  int n = 0;
  void add(const std::vector<double>& m) {
    for (int r = 0; r < kRegions; ++r) {
      sum[r] += m[r];
      sum2[r] += m[r] * m[r];
    }
    ++n;
  }
  double mean(int r) const { return sum[r] / n; }
  double variance(int r) const {  // of one batch mean (unbiased)
    return std::max(0.0, (sum2[r] - sum[r] * sum[r] / n) / (n - 1));
  }
};

}  // namespace

const char* region_name(int region) {
  static const char* names[kRegions] = {"whole", "top-left", "top-right", "bottom-left", "bottom-right"};
  return names[region];
}

double Comparison::worst_abs_z() const {
  double w = 0;
  for (int r = 0; r < kRegions; ++r) w = std::max(w, std::abs(z[r]));
  return w;
}

bool streams_overlap(uint32_t seed_a, int64_t na, uint32_t seed_b, int64_t nb) {
  const uint64_t a = gpu::pcg_hash(seed_a), b = gpu::pcg_hash(seed_b);
  const uint64_t ab = (b - a) & 0xffffffffu, ba = (a - b) & 0xffffffffu;  // distances mod 2^32
  return ab < static_cast<uint64_t>(na) || ba < static_cast<uint64_t>(nb);
}

uint32_t choose_soak_seed(uint32_t from, int64_t wrap_at, int spp, int64_t* wrap_sample) {
  const int64_t lo = wrap_at - wrap_at / 10, hi = wrap_at + wrap_at / 10;
  for (uint32_t s = from;; ++s) {
    const int64_t w = (int64_t(1) << 32) - int64_t(gpu::pcg_hash(s));  // sample index of the wrap
    if (w >= std::max<int64_t>(lo, 1) && w <= hi && w % spp == 0) {
      *wrap_sample = w;
      return s;
    }
    if (s == 0xffffffffu) throw std::runtime_error("no seed wraps there");
  }
}

SoakReport run_soak(const SoakConfig& c, std::FILE* log) {
  SoakReport rep;
  const Scene base_scene = load_project(c.project);
  const int64_t n_final = c.frames * c.spp;
  if (n_final >= (int64_t(1) << 24))
    throw std::runtime_error("more than 2^24 samples per pixel: beyond float32's exact counts");
  rep.seed = choose_soak_seed(1, n_final / 2, c.spp, &rep.wrap_sample);
  Scene base = base_scene;
  base.render.seed = rep.seed;
  rep.gl_renderer = gl_renderer_name();

  if (n_final > kViewportMaxSamples) throw std::runtime_error("more samples per pixel than the viewport traces");
  // The editor's viewport at full resolution, with c.spp samples every frame instead of the
  // frame budget's (so that runs are repeatable).
  ViewportRenderer viewport;
  GpuRenderer& renderer = viewport.renderer();
  ViewportRequest request;
  request.width = c.width;
  request.height = c.height;
  request.resolution = ViewportResolution::full;
  request.samples_per_frame = c.spp;
  auto frame = [&](const Scene& scene) {
    const ViewportFrame out = viewport.render(scene, request);
    if (!out.stats.scene_problem.empty()) throw std::runtime_error("an edit made the scene invalid: " + out.stats.scene_problem);
    return out.stats;
  };
  // A reading is the smallest heap and RSS over kSettleFrames frames of the scene as it is (no
  // edit): a driver frees some objects a frame or two after they were replaced (the 2 MiB sky
  // texture of default.glint after an environment edit), which is not a leak.
  auto reading = [&](const char* when, int64_t f, const Scene& scene) {
    MemoryReading m;
    m.when = when;
    m.frame = f;
    m.rss = resident();
    m.heap_bytes = heap_in_use_bytes();
    for (int i = 0; i < kSettleFrames; ++i) {
      frame(scene);
      const Resident now = resident();
      if (now.anon_kib < m.rss.anon_kib) m.rss = now;
      m.heap_bytes = std::min(m.heap_bytes, heap_in_use_bytes());
    }
    m.heap_held = heap_held_bytes();
    m.gl = count_gl_objects();
    rep.memory.push_back(m);
    if (log)
      std::fprintf(log, "soak: %s (frame %lld): RSS %lld KiB (anonymous %lld, files %lld), heap %lld B (held %lld B), %s\n",
                   when, (long long)f, (long long)m.rss.total_kib, (long long)m.rss.anon_kib, (long long)m.rss.file_kib,
                   (long long)m.heap_bytes, (long long)m.heap_held, describe(m.gl).c_str());
  };
  auto maybe_read_back = [&](int64_t f) {
    if (c.readback_every > 0 && f % c.readback_every == c.readback_every - 1) {
      Image display = renderer.read_display();
      if (display.pixels.empty()) throw std::runtime_error("empty display read-back");
      ++rep.readbacks;
    }
  };

  // What the soak itself keeps, allocated before the first memory reading. That includes what
  // the driver allocates to answer the object count's glIs* queries: Mesa 25 allocates about
  // 3 MB the first time names 1 .. 65536 are asked about (a step of 3.2 MB right after the
  // first reading, whatever the number of edits and warm-up frames), and nothing after that.
  count_gl_objects();
  std::vector<int64_t> checkpoint_frames;
  for (int i = 1; i <= c.checkpoints; ++i) checkpoint_frames.push_back(c.frames * i / c.checkpoints);
  const int64_t wrap_frame = rep.wrap_sample / c.spp;  // samples before it: all unwrapped
  checkpoint_frames.push_back(wrap_frame);
  std::sort(checkpoint_frames.begin(), checkpoint_frames.end());
  std::vector<std::pair<int64_t, std::vector<double>>> readings;  // samples, region means
  readings.reserve(c.checkpoints + 1);
  for (int i = 0; i <= c.checkpoints; ++i) readings.emplace_back(0, std::vector<double>(kRegions));
  std::vector<float> final_pixels(static_cast<size_t>(c.width) * c.height * 4);
  rep.memory.reserve(3);
  int readings_used = 0;

  // Phase 1: edits.
  auto t0 = Clock::now();
  Scene s = base;
  int64_t exposure_steps = 0;
  const int64_t edit_total = c.warmup_frames + c.edit_frames;
  for (int64_t f = 0; f < edit_total; ++f) {
    if (f > 0) {
      apply_edit(s, base, f - 1);
      ++rep.edits;
    }
    const bool exposure_frame = c.exposure_every > 0 && f % c.exposure_every == c.exposure_every - 1;
    if (exposure_frame) s.display.exposure = exposure_value(++exposure_steps);
    const FrameStats r = frame(s);
    if (f > 0 && r.restarted) ++rep.edit_resets;
    maybe_read_back(f);
    if (c.after_frame) c.after_frame(f);
    if (f + 1 == c.warmup_frames) reading("after warm-up", f + 1, s);
  }
  reading("after the edits", edit_total, s);
  rep.seconds_edits = seconds_since(t0);

  // Phase 2: one long accumulation of the unedited scene.
  t0 = Clock::now();
  s = base;
  Scene restart = base;  // so that frame 0 restarts even if phase 1 ended on the unedited scene
  restart.render.seed = base.render.seed + 1;
  renderer.sync(restart, c.width, c.height);
  for (int64_t f = 0; f < c.frames; ++f) {
    const bool exposure_frame = c.exposure_every > 0 && f % c.exposure_every == c.exposure_every - 1;
    if (exposure_frame) {
      s.display.exposure = exposure_value(++exposure_steps);
      ++rep.exposure_changes;
    }
    const FrameStats r = frame(s);
    if (f == 0 && !r.restarted) throw std::runtime_error("the unedited scene did not restart the accumulation");
    if (f > 0 && r.restarted) ++rep.exposure_resets;
    maybe_read_back(f);
    if (c.after_frame) c.after_frame(f);
    if (std::binary_search(checkpoint_frames.begin(), checkpoint_frames.end(), f + 1)) {
      Image img = renderer.read_accumulation();
      auto& [n, means] = readings[readings_used++];
      n = renderer.sample_count();
      const std::vector<double> m = region_means(img);
      std::copy(m.begin(), m.end(), means.begin());
      if (f + 1 == c.frames) std::copy(img.pixels.begin(), img.pixels.end(), final_pixels.begin());
      if (log) std::fprintf(log, "soak: %lld spp, whole-image mean %.7f (%.1f s)\n", (long long)n, means[0],
                            seconds_since(t0));
    }
  }
  rep.final_samples = renderer.sample_count();
  if (rep.final_samples != n_final) throw std::runtime_error("the sample count is not frames x spp");
  reading("after the accumulation", edit_total + c.frames, s);  // settle frames come after the last checkpoint
  rep.seconds_accumulation = seconds_since(t0);

  // Paired: the same seed (the same samples) in passes of paired_spp.
  if (c.paired_spp > 0) {
    Scene other = base;
    other.render.seed = base.render.seed + 1;
    renderer.sync(other, c.width, c.height);  // then back: a restart with the soak's seed
    renderer.sync(base, c.width, c.height);
    RenderSessionOptions paired_passes;
    paired_passes.target.samples = n_final;
    paired_passes.batch = {.first_batch = c.paired_spp, .max_batch = c.paired_spp};
    RenderSession(renderer, paired_passes).run();
    Image paired = renderer.read_accumulation();
    Image soaked = paired;
    std::copy(final_pixels.begin(), final_pixels.end(), soaked.pixels.begin());
    const std::vector<double> a = region_means(soaked), b = region_means(paired);
    for (int r = 0; r < kRegions; ++r) rep.paired_relative[r] = b[r] > 0 ? (a[r] - b[r]) / b[r] : 0;
    // Pixels relative to their own value, or to 1e-3 of the image's mean for darker ones.
    for (int y = 0; y < paired.height; ++y)
      for (int x = 0; x < paired.width; ++x) {
        const double pa = luminance(soaked.at(x, y)), pb = luminance(paired.at(x, y));
        rep.paired_worst_pixel_relative =
            std::max(rep.paired_worst_pixel_relative, std::abs(pa - pb) / std::max(pb, 1e-3 * b[0]));
      }
  }

  // Phase 3: the reference, from independent short accumulations whose sample streams share
  // no index with the soak's or each other's.
  t0 = Clock::now();
  BatchSums batches;
  std::vector<uint32_t> used{base.render.seed};
  std::vector<int64_t> used_n{n_final};
  uint32_t candidate = base.render.seed + 1000;
  while (batches.n < c.reference_batches) {
    const uint32_t seed = candidate++;
    bool clash = false;
    for (size_t i = 0; i < used.size() && !clash; ++i) clash = streams_overlap(used[i], used_n[i], seed, c.reference_spp);
    if (clash) continue;
    used.push_back(seed);
    used_n.push_back(c.reference_spp);
    Scene b = base;
    b.render.seed = seed;
    renderer.set_options(request.estimator);
    renderer.sync(b, c.width, c.height);
    renderer.trace(c.reference_spp);
    batches.add(region_means(renderer.read_accumulation()));
  }
  rep.seconds_reference = seconds_since(t0);

  // Comparisons. A batch mean's variance v (per region) is that of reference_spp samples, so
  // one sample's is v * reference_spp; the soak's mean of n samples then has variance
  // v * reference_spp / n, and the reference's own mean v / batches.
  auto compare = [&](const std::string& what, int64_t n, const std::vector<double>& soak) {
    Comparison cmp;
    cmp.what = what;
    cmp.samples = n;
    for (int r = 0; r < kRegions; ++r) {
      const double v = batches.variance(r);
      cmp.soak[r] = soak[r];
      cmp.reference[r] = batches.mean(r);
      cmp.se[r] = std::sqrt(v * c.reference_spp / double(n) + v / batches.n);
      cmp.z[r] = cmp.se[r] > 0 ? (soak[r] - cmp.reference[r]) / cmp.se[r] : (soak[r] == cmp.reference[r] ? 0 : 1e9);
    }
    rep.comparisons.push_back(cmp);
  };
  const std::vector<double>* at_wrap = nullptr;
  int64_t n_wrap = 0;
  readings.resize(readings_used);
  for (const auto& [n, m] : readings) {
    compare("checkpoint", n, m);
    if (n == wrap_frame * c.spp) {
      at_wrap = &m;
      n_wrap = n;
    }
  }
  if (at_wrap && n_wrap < n_final) {
    // The samples after the wrap alone: (N m_N - n_w m_w) / (N - n_w), in double.
    std::vector<double> after(kRegions);
    const std::vector<double>& end = readings.back().second;
    for (int r = 0; r < kRegions; ++r)
      after[r] = (double(n_final) * end[r] - double(n_wrap) * (*at_wrap)[r]) / double(n_final - n_wrap);
    compare("after the wrap", n_final - n_wrap, after);
  }
  rep.relative_se_whole = rep.comparisons.empty() ? 0
                          : std::sqrt(batches.variance(0) * c.reference_spp / double(n_final)) / std::abs(batches.mean(0));
  return rep;
}

// RSS counts pages, including freed memory that malloc keeps, so it ratchets up to the peak of
// what was alive at once; its file-backed part also rises when llvmpipe first compiles a shader
// state and pages in more of LLVM. Measured on default.glint: anonymous RSS +4996 KiB from frame
// 1000 to the end with the heap in use flat within 3 KB and the memory malloc holds +5124 KiB,
// the same after 10^4 and 3 x 10^4 edits (a plateau of fragmentation around the 2 MiB sky
// texture that environment edits re-create, not growth). So malloc's memory is checked by the
// heap in use (kHeapGrowthBound), and RSS by what malloc does not explain: anonymous RSS growth
// minus the growth of what malloc holds, i.e. driver mappings and JIT code. Its bound is 4 MiB,
// twice the largest object a frame re-creates in the example projects, or 2% of the first
// reading if larger; a leak outside malloc of 42 bytes per frame over the 10^5-frame
// accumulation, or 420 bytes per edit over 10^4 edits, exceeds it.
int64_t rss_growth_bound_kib(const SoakReport& report) {
  const int64_t first = report.memory.empty() ? 0 : report.memory.front().rss.anon_kib;
  return std::max<int64_t>(4096, first / 50);
}

int64_t unexplained_rss_growth_kib(const SoakReport& report) {
  if (report.memory.size() < 2) return 0;
  const MemoryReading &first = report.memory.front(), &last = report.memory.back();
  return (last.rss.anon_kib - first.rss.anon_kib) - (last.heap_held - first.heap_held) / 1024;
}

std::vector<std::string> failures(const SoakConfig& c, const SoakReport& rep) {
  std::vector<std::string> f;
  char text[256];
  if (rep.edit_resets != rep.edits) {
    std::snprintf(text, sizeof text, "%lld of %lld edits restarted the accumulation", (long long)rep.edit_resets,
                  (long long)rep.edits);
    f.push_back(text);
  }
  if (rep.exposure_resets != 0) f.push_back("an exposure change restarted the accumulation");
  if (rep.memory.size() >= 2) {
    const MemoryReading &first = rep.memory.front(), &last = rep.memory.back();
    for (const MemoryReading& m : rep.memory)
      if (!(m.gl == first.gl)) f.push_back("GL objects " + m.when + ": " + describe(m.gl) + ", after warm-up " + describe(first.gl));
    if (last.heap_bytes - first.heap_bytes > kHeapGrowthBound) {
      std::snprintf(text, sizeof text, "heap grew by %lld bytes (bound %lld)", (long long)(last.heap_bytes - first.heap_bytes),
                    (long long)kHeapGrowthBound);
      f.push_back(text);
    }
    if (unexplained_rss_growth_kib(rep) > rss_growth_bound_kib(rep)) {
      std::snprintf(text, sizeof text,
                    "RSS grew by %lld KiB of anonymous memory that malloc does not hold (bound %lld KiB)",
                    (long long)unexplained_rss_growth_kib(rep), (long long)rss_growth_bound_kib(rep));
      f.push_back(text);
    }
  }
  for (const Comparison& cmp : rep.comparisons)
    for (int r = 0; r < kRegions; ++r)
      if (!(std::abs(cmp.z[r]) <= c.k_sigma)) {
        std::snprintf(text, sizeof text, "%s at %lld spp, %s: %.7f against %.7f, %.2f standard errors", cmp.what.c_str(),
                      (long long)cmp.samples, region_name(r), cmp.soak[r], cmp.reference[r], cmp.z[r]);
        f.push_back(text);
      }
  if (c.paired_spp > 0) {
    for (int r = 0; r < kRegions; ++r)
      if (!(std::abs(rep.paired_relative[r]) < kStatedPrecision)) {
        std::snprintf(text, sizeof text, "accumulation drift, %s: %.3g (relative) against the same samples in passes of %d",
                      region_name(r), rep.paired_relative[r], c.paired_spp);
        f.push_back(text);
      }
    if (!(rep.paired_worst_pixel_relative < kStatedPrecision)) {
      std::snprintf(text, sizeof text, "accumulation drift of a pixel: %.3g (relative) against the same samples in passes of %d",
                    rep.paired_worst_pixel_relative, c.paired_spp);
      f.push_back(text);
    }
  }
  return f;
}

std::string format_report(const SoakConfig& c, const SoakReport& rep) {
  std::string out;
  char line[512];
  auto add = [&](const char* fmt, auto... args) {
    std::snprintf(line, sizeof line, fmt, args...);
    out += line;
  };
  add("soak of %s at %dx%d, %lld frames of %d spp, on %s\n", c.project.filename().string().c_str(), c.width, c.height,
      (long long)c.frames, c.spp, rep.gl_renderer.c_str());
  add("seed %u: the sample-stream index wraps at sample %lld\n", rep.seed, (long long)rep.wrap_sample);
  add("phase 1: %lld edits (%lld restarted the accumulation), %.1f s\n", (long long)rep.edits,
      (long long)rep.edit_resets, rep.seconds_edits);
  add("phase 2: %lld frames, %lld spp, %lld exposure changes (%lld restarts), %lld display read-backs, %.1f s\n",
      (long long)c.frames, (long long)rep.final_samples, (long long)rep.exposure_changes,
      (long long)rep.exposure_resets, (long long)rep.readbacks, rep.seconds_accumulation);
  add("phase 3: reference of %d batches x %d spp, %.1f s\n", c.reference_batches, c.reference_spp,
      rep.seconds_reference);
  for (const MemoryReading& m : rep.memory)
    add("memory %-24s frame %7lld  RSS %7lld KiB (anon %7lld, files %7lld)  heap %10lld B  %s\n", m.when.c_str(),
        (long long)m.frame, (long long)m.rss.total_kib, (long long)m.rss.anon_kib, (long long)m.rss.file_kib,
        (long long)m.heap_bytes, describe(m.gl).c_str());
  if (rep.memory.size() >= 2)
    add("growth after warm-up: RSS %+lld KiB, anonymous %+lld KiB (not held by malloc %+lld KiB, bound %lld KiB), "
        "files %+lld KiB; heap in use %+lld B (bound %lld B), held by malloc %+lld B\n",
        (long long)(rep.memory.back().rss.total_kib - rep.memory.front().rss.total_kib),
        (long long)(rep.memory.back().rss.anon_kib - rep.memory.front().rss.anon_kib),
        (long long)unexplained_rss_growth_kib(rep), (long long)rss_growth_bound_kib(rep),
        (long long)(rep.memory.back().rss.file_kib - rep.memory.front().rss.file_kib),
        (long long)(rep.memory.back().heap_bytes - rep.memory.front().heap_bytes), (long long)kHeapGrowthBound,
        (long long)(rep.memory.back().heap_held - rep.memory.front().heap_held));
  add("%-16s %9s %-13s %12s %12s %10s %8s\n", "comparison", "spp", "region", "soak", "reference", "rel.diff", "z");
  for (const Comparison& cmp : rep.comparisons)
    for (int r = 0; r < kRegions; ++r)
      add("%-16s %9lld %-13s %12.7f %12.7f %+9.4f%% %+8.2f\n", cmp.what.c_str(), (long long)cmp.samples,
          region_name(r), cmp.soak[r], cmp.reference[r], 100 * (cmp.soak[r] - cmp.reference[r]) / cmp.reference[r],
          cmp.z[r]);
  add("relative standard error of the final whole-image mean: %.4f%%\n", 100 * rep.relative_se_whole);
  if (c.paired_spp > 0)
    add("paired (same samples in passes of %d), relative: whole %+.3g, quadrants %+.3g %+.3g %+.3g %+.3g, worst pixel %.3g\n",
        c.paired_spp, rep.paired_relative[0], rep.paired_relative[1], rep.paired_relative[2], rep.paired_relative[3],
        rep.paired_relative[4], rep.paired_worst_pixel_relative);
  return out;
}

}  // namespace glint::soak
