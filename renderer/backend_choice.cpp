#include "renderer/backend_choice.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <epoxy/gl.h>
#include <nlohmann/json.hpp>

#include "renderer/state_file.h"
#include "renderer/gl_context.h"
#include "renderer/gpu_renderer.h"
#include "renderer/llvmpipe_threads.h"
#include "renderer/scene_digest.h"
#include "renderer/shader_sources.h"
#include "renderer/stopwatch.h"

namespace glint {
namespace {

using Clock = std::chrono::steady_clock;

// The timing: kTimingRounds alternating passes of kTimingSpp samples per back end at
// kTimingSize x kTimingSize. Passes of 32 samples take 15-35 ms each on llvmpipe: in passes of
// 8 (a few ms) a fixed cost per fragment-shader pass (at least partly llvmpipe's threads
// sharing a CPU, see llvmpipe_threads.h) made the fragment shader look 0.7-1.1x
// the compute shader on the timing scene on Mesa 25, where `glint render`'s long passes trace
// it about 1.3x as fast (bench/reports/THROUGHPUT.md, "The back-end timing's passes").
constexpr int kTimingSize = 128, kTimingRounds = 5, kTimingSpp = 32;

// The workload the two entry points differ on most: long matte paths, no textures, no
// emitters, so the program is small and compiles fast.
Scene timing_scene() {
  Scene s;
  s.camera.position = {0, 1.5f, 6};
  s.camera.target = {0, 0.5f, 0};
  s.camera.up = {0, 1, 0};
  s.environment.color = {0.8f, 0.85f, 1.0f};
  s.render.max_bounces = 4;
  Material floor;
  floor.name = "floor";
  floor.color = {0.6f, 0.6f, 0.6f};
  Material ball;
  ball.name = "ball";
  ball.color = {0.7f, 0.4f, 0.3f};
  s.materials = {floor, ball};
  Sphere ground;
  ground.name = "ground";
  ground.center = {0, -1000, 0};
  ground.radius = 1000;
  ground.material = "floor";
  s.spheres.push_back(ground);
  for (int i = 0; i < 8; ++i) {
    Sphere b;
    b.name = "ball" + std::to_string(i);
    b.center = {-2.8f + 0.8f * i, 0.35f, -0.5f * (i % 3)};
    b.radius = 0.35f;
    b.material = "ball";
    s.spheres.push_back(b);
  }
  return s;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// The cache as read: an object whose "devices" is an object, or an empty object where the file
// is absent or is anything else (a FIFO, a folder, too large, not JSON), with `note` saying
// which. The cache is untrusted input: a bad one is timed again and rewritten.
nlohmann::json read_cache(const std::filesystem::path& file, std::string& note) {
  try {
    const std::optional<std::string> text = read_state_file(file, kMaxStateFileBytes);
    if (!text) return nlohmann::json::object();
    nlohmann::json j = nlohmann::json::parse(*text, nullptr, false);
    if (!j.is_discarded() && j.is_object() && j.contains("devices") && j["devices"].is_object()) return j;
    note = file.string() + ": unreadable backend cache (not a JSON object with \"devices\"), timed again";
  } catch (const StateFileError& e) {
    note = std::string(e.what()) + " (unreadable backend cache, timed again)";
  }
  return nlohmann::json::object();
}

// The choice a cache entry records, or nullopt where any of its fields is missing or mistyped
// (then the device is timed again and the entry replaced).
std::optional<BackendChoice> cached_choice(const nlohmann::json& entry) {
  if (!entry.is_object()) return std::nullopt;
  const auto backend = entry.find("backend");
  const auto fragment = entry.find("fragment_spp_s");
  const auto compute = entry.find("compute_spp_s");
  if (backend == entry.end() || !backend->is_string() || fragment == entry.end() || !fragment->is_number() ||
      compute == entry.end() || !compute->is_number())
    return std::nullopt;
  const auto parsed = parse_backend(backend->get<std::string>());
  if (!parsed) return std::nullopt;
  BackendChoice choice;
  choice.backend = *parsed;
  choice.from_cache = true;
  choice.fragment_spp_s = fragment->get<double>();
  choice.compute_spp_s = compute->get<double>();
  return choice;
}

}  // namespace

std::string device_key() {
  const GLubyte* vendor = glGetString(GL_VENDOR);
  // The shaders too: a build whose path tracer changed may be faster on the other entry point;
  // and how they are timed, so that a changed timing times again.
  Hasher shaders;
  shaders.value(shader_source("trace.frag"));
  shaders.value(shader_source("trace.comp"));
  for (int v : {kTimingSize, kTimingRounds, kTimingSpp}) shaders.value(v);
  shaders.value(llvmpipe_thread_pinning_enabled() ? 1 : 0);  // short passes speed up with it
  char digest[17];
  std::snprintf(digest, sizeof digest, "%016llx", static_cast<unsigned long long>(shaders.result()));
  return std::string(vendor ? reinterpret_cast<const char*>(vendor) : "unknown") + " | " +
         gl_renderer_name() + " | " + gl_version_string() + " | shaders " + digest;
}

std::optional<std::filesystem::path> default_backend_cache_file() {
  // The XDG Base Directory specification: a relative path in XDG_CACHE_HOME is invalid and
  // ignored (else the cache would land in whatever folder a render starts in).
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg == '/')
    return std::filesystem::path(xdg) / "glint" / "backend.json";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::filesystem::path(home) / ".cache" / "glint" / "backend.json";
  return std::nullopt;
}

BackendTiming time_backends() {
  const Scene scene = timing_scene();
  std::unique_ptr<GpuRenderer> renderers[2];
  for (int b = 0; b < 2; ++b) {
    GpuRendererOptions options;
    options.backend = b ? TraceBackend::compute : TraceBackend::fragment;
    renderers[b] = std::make_unique<GpuRenderer>(options);
    renderers[b]->sync(scene, kTimingSize, kTimingSize);
    renderers[b]->prepare_specialised_program();
    renderers[b]->trace(1);  // the first pass may still set things up in the driver
    glFinish();
  }
  std::vector<double> rate[2];
  for (int round = 0; round < kTimingRounds; ++round)
    for (int b = 0; b < 2; ++b) {
      const auto start = Clock::now();
      renderers[b]->trace(kTimingSpp);
      glFinish();
      rate[b].push_back(kTimingSpp / std::max(seconds_since(start), 1e-9));
    }
  return {median(rate[0]), median(rate[1])};
}

bool fewer_llvmpipe_tiles_than_threads(int width, int height, int threads) {
  return int64_t(llvmpipe_tiles_across(width)) * llvmpipe_tiles_across(height) < threads;
}

bool prefers_compute(const BackendTiming& t) {
  return t.compute_spp_s > kComputeMargin * t.fragment_spp_s;
}

BackendChoice choose_backend(const std::optional<std::filesystem::path>& cache_file) {
  const auto start = Clock::now();
  BackendChoice choice;
  const std::string key = device_key();
  nlohmann::json cache = nlohmann::json::object();
  if (cache_file) {
    cache = read_cache(*cache_file, choice.note);
    if (cache.contains("devices") && cache["devices"].contains(key)) {
      if (auto cached = cached_choice(cache["devices"][key])) {
        cached->seconds = seconds_since(start);
        return *cached;
      }
      choice.note = cache_file->string() + ": unreadable backend cache entry for this device (a field missing "
                    "or mistyped), timed again";
    }
  }
  const BackendTiming timing = time_backends();
  choice.fragment_spp_s = timing.fragment_spp_s;
  choice.compute_spp_s = timing.compute_spp_s;
  choice.backend = prefers_compute(timing) ? TraceBackend::compute : TraceBackend::fragment;
  if (cache_file) {
    if (!cache.contains("devices")) cache = {{"devices", nlohmann::json::object()}};
    cache["devices"][key] = {{"backend", backend_name(choice.backend)},
                             {"fragment_spp_s", choice.fragment_spp_s},
                             {"compute_spp_s", choice.compute_spp_s}};
    try {
      std::error_code ec;
      std::filesystem::create_directories(cache_file->parent_path(), ec);
      const std::string text = cache.dump(2) + "\n";
      write_state_file(*cache_file, text);
    } catch (const std::exception& e) {
      choice.note = std::string("backend cache not written: ") + e.what();
    }
  }
  choice.seconds = seconds_since(start);
  return choice;
}

}  // namespace glint
