#include "renderer/denoiser.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <vector>

#include "renderer/oidn_api.h"

#if defined(__linux__)
#include <dlfcn.h>
#endif

namespace glint {
namespace {

// The C API, resolved once per process.
struct OidnLibrary {
  oidn::NewDeviceFn new_device = nullptr;
  oidn::CommitDeviceFn commit_device = nullptr;
  oidn::GetDeviceIntFn get_device_int = nullptr;
  oidn::GetDeviceErrorFn get_device_error = nullptr;
  oidn::ReleaseDeviceFn release_device = nullptr;
  oidn::NewBufferFn new_buffer = nullptr;
  oidn::WriteBufferFn write_buffer = nullptr;
  oidn::ReadBufferFn read_buffer = nullptr;
  oidn::ReleaseBufferFn release_buffer = nullptr;
  oidn::NewFilterFn new_filter = nullptr;
  oidn::SetFilterImageFn set_filter_image = nullptr;
  oidn::UnsetFilterImageFn unset_filter_image = nullptr;
  oidn::SetFilterBoolFn set_filter_bool = nullptr;
  oidn::SetFilterIntFn set_filter_int = nullptr;
  oidn::CommitFilterFn commit_filter = nullptr;
  oidn::ExecuteFilterFn execute_filter = nullptr;
  oidn::ReleaseFilterFn release_filter = nullptr;
  std::optional<std::string> unavailable;  // why not, when it could not be loaded
};

#if defined(__linux__) && defined(__x86_64__)
// The folders to look in, first match wins: $GLINT_OIDN_DIR, the executable's own folder (the
// build copies the libraries there), ../lib/glint from it (an installed glint: bin/glint and
// lib/glint/, cmake/Packaging.cmake, whatever the prefix); then the loader's search path.
std::vector<std::filesystem::path> library_folders() {
  std::vector<std::filesystem::path> folders;
  if (const char* dir = std::getenv("GLINT_OIDN_DIR"); dir && *dir) folders.emplace_back(dir);
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    folders.push_back(exe.parent_path());
    folders.push_back(exe.parent_path().parent_path() / "lib" / "glint");
  }
  return folders;
}

// Returns the handle, or nullptr with `why` holding the first real reason: a library found
// but not loadable (corrupt, of another architecture, a missing dependency) is reported as
// such, not as the "not found" of the last place tried.
void* open_library(std::string& why) {
  // Intel's libraries find each other through an RPATH of $ORIGIN/../lib, which does not hold
  // next to an executable: their dependencies are loaded first, by full path, so that the
  // loader finds them already loaded by their sonames. OIDN itself loads its device plugins
  // (the CPU one; the CUDA one where a driver is present) from its core library's folder.
  for (const auto& folder : library_folders()) {
    const auto main = folder / "libOpenImageDenoise.so.2.5.1";
    if (!std::filesystem::exists(main)) continue;
    for (const char* dependency : {"libtbb.so.12", "libOpenImageDenoise_core.so.2.5.1"})
      dlopen((folder / dependency).c_str(), RTLD_NOW | RTLD_GLOBAL);
    if (void* handle = dlopen(main.c_str(), RTLD_NOW | RTLD_LOCAL)) return handle;
    if (why.empty()) {
      const char* error = dlerror();
      why = main.string() + " cannot be loaded (" + (error ? error : "unknown reason") + ")";
    }
  }
  if (void* handle = dlopen("libOpenImageDenoise.so.2", RTLD_NOW | RTLD_LOCAL)) return handle;
  if (why.empty()) {
    const char* error = dlerror();
    why = std::string("libOpenImageDenoise.so.2.5.1 not found next to the executable, in ../lib/glint from it, in "
                      "$GLINT_OIDN_DIR or on the library path") + (error ? std::string(" (") + error + ")" : std::string()) +
          "; scripts/setup.sh fetches it and the build copies it next to glint";
  }
  return nullptr;
}

template <typename Fn>
bool resolve(void* handle, const char* name, Fn& fn, OidnLibrary& lib) {
  fn = reinterpret_cast<Fn>(dlsym(handle, name));
  if (!fn && !lib.unavailable) lib.unavailable = std::string("libOpenImageDenoise lacks ") + name;
  return fn != nullptr;
}

OidnLibrary load_library() {
  OidnLibrary lib;
  std::string why;
  void* handle = open_library(why);
  if (!handle) {
    lib.unavailable = why;
    return lib;
  }
  resolve(handle, "oidnNewDevice", lib.new_device, lib);
  resolve(handle, "oidnCommitDevice", lib.commit_device, lib);
  resolve(handle, "oidnGetDeviceInt", lib.get_device_int, lib);
  resolve(handle, "oidnGetDeviceError", lib.get_device_error, lib);
  resolve(handle, "oidnReleaseDevice", lib.release_device, lib);
  resolve(handle, "oidnNewBuffer", lib.new_buffer, lib);
  resolve(handle, "oidnWriteBuffer", lib.write_buffer, lib);
  resolve(handle, "oidnReadBuffer", lib.read_buffer, lib);
  resolve(handle, "oidnReleaseBuffer", lib.release_buffer, lib);
  resolve(handle, "oidnNewFilter", lib.new_filter, lib);
  resolve(handle, "oidnSetFilterImage", lib.set_filter_image, lib);
  resolve(handle, "oidnUnsetFilterImage", lib.unset_filter_image, lib);
  resolve(handle, "oidnSetFilterBool", lib.set_filter_bool, lib);
  resolve(handle, "oidnSetFilterInt", lib.set_filter_int, lib);
  resolve(handle, "oidnCommitFilter", lib.commit_filter, lib);
  resolve(handle, "oidnExecuteFilter", lib.execute_filter, lib);
  resolve(handle, "oidnReleaseFilter", lib.release_filter, lib);
  return lib;  // the handle stays open for the life of the process
}
#else
OidnLibrary load_library() {
  OidnLibrary lib;
  lib.unavailable = "Open Image Denoise is shipped for x86_64 Linux only";
  return lib;
}
#endif

const OidnLibrary& library() {
  static const OidnLibrary lib = load_library();  // thread-safe initialisation
  return lib;
}

const char* device_type_name(int type) {
  switch (type) {
    case oidn::kDeviceCpu: return "CPU";
    case oidn::kDeviceSycl: return "SYCL";
    case oidn::kDeviceCuda: return "CUDA";
    case oidn::kDeviceHip: return "HIP";
    case oidn::kDeviceMetal: return "Metal";
    default: return "unknown";
  }
}

}  // namespace

std::optional<std::string> denoising_unavailable() { return library().unavailable; }

bool denoising_available_or_warn_once(const std::string& who) {
  const auto why = denoising_unavailable();
  if (!why) return true;
  static std::once_flag warned;
  std::call_once(warned, [&] {
    std::fprintf(stderr, "%s: denoising is unavailable (%s); continuing without it\n", who.c_str(),
                 why->c_str());
  });
  return false;
}

struct Denoiser::State {
  const OidnLibrary& lib = library();
  oidn::Device device = nullptr;
  oidn::Filter filter = nullptr;
  oidn::Buffer buffers[4] = {};  // colour, albedo, normal, output
  int width = 0, height = 0;
  bool has_albedo = false, has_normal = false;
  DenoiseQuality quality = DenoiseQuality::high;

  void check(const char* what) const {
    const char* message = nullptr;
    if (lib.get_device_error(device, &message) != oidn::kErrorNone)
      throw DenoiseError(std::string("Open Image Denoise: ") + what + ": " +
                         (message ? message : "unknown error"));
  }
  void release_images() {
    for (auto& b : buffers)
      if (b) lib.release_buffer(b), b = nullptr;
    if (filter) lib.release_filter(filter), filter = nullptr;
  }
  ~State() {
    release_images();
    if (device) lib.release_device(device);
  }
};

Denoiser::Denoiser(DenoiseQuality quality) : state_(std::make_unique<State>()) {
  if (const auto why = denoising_unavailable()) throw DenoiseError("denoising is unavailable: " + *why);
  State& s = *state_;
  s.quality = quality;
  s.device = s.lib.new_device(oidn::kDeviceDefault);
  if (!s.device) throw DenoiseError("Open Image Denoise: no supported device");
  s.lib.commit_device(s.device);
  s.check("creating the device");
  device_name_ = device_type_name(s.lib.get_device_int(s.device, "type"));
}

Denoiser::~Denoiser() = default;

namespace {
std::vector<float> rgb_of(const Image& image, bool clamp01) {
  std::vector<float> rgb(static_cast<size_t>(image.width) * image.height * 3);
  for (size_t i = 0, n = rgb.size() / 3; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const float v = image.pixels[i * 4 + c];
      rgb[i * 3 + c] = clamp01 ? std::min(std::max(v, 0.0f), 1.0f) : v;
    }
  return rgb;
}
}  // namespace

Image Denoiser::denoise(const Image& color, const Image* albedo, const Image* normal) {
  State& s = *state_;
  if (normal && !albedo) throw DenoiseError("a normal image needs an albedo image too");
  for (const Image* aux : {albedo, normal})
    if (aux && (aux->width != color.width || aux->height != color.height))
      throw DenoiseError("the auxiliary images must have the colour's size");
  if (color.width <= 0 || color.height <= 0) throw DenoiseError("cannot denoise an empty image");
  const size_t bytes = static_cast<size_t>(color.width) * color.height * 3 * sizeof(float);
  // A new filter only when the size or the inputs change: OIDN's documentation warns that
  // creating one can be expensive.
  if (!s.filter || s.width != color.width || s.height != color.height ||
      s.has_albedo != (albedo != nullptr) || s.has_normal != (normal != nullptr)) {
    s.release_images();
    s.width = color.width;
    s.height = color.height;
    s.has_albedo = albedo != nullptr;
    s.has_normal = normal != nullptr;
    s.filter = s.lib.new_filter(s.device, "RT");
    s.check("creating the RT filter");
    const char* names[4] = {"color", "albedo", "normal", "output"};
    for (int i = 0; i < 4; ++i) {
      if ((i == 1 && !albedo) || (i == 2 && !normal)) continue;
      s.buffers[i] = s.lib.new_buffer(s.device, bytes);
      s.check("allocating an image buffer");
      s.lib.set_filter_image(s.filter, names[i], s.buffers[i], oidn::kFormatFloat3, s.width,
                             s.height, 0, 0, 0);
    }
    s.lib.set_filter_bool(s.filter, "hdr", true);  // linear radiance, not [0,1]
    s.lib.set_filter_int(s.filter, "quality",
                         s.quality == DenoiseQuality::fast ? oidn::kQualityFast : oidn::kQualityHigh);
    s.lib.commit_filter(s.filter);
    s.check("committing the RT filter");
  }
  s.lib.write_buffer(s.buffers[0], 0, bytes, rgb_of(color, false).data());
  if (albedo) s.lib.write_buffer(s.buffers[1], 0, bytes, rgb_of(*albedo, true).data());
  if (normal) s.lib.write_buffer(s.buffers[2], 0, bytes, rgb_of(*normal, false).data());
  s.lib.execute_filter(s.filter);
  s.check("denoising");
  std::vector<float> rgb(bytes / sizeof(float));
  s.lib.read_buffer(s.buffers[3], 0, bytes, rgb.data());
  Image out = color;
  for (size_t i = 0, n = rgb.size() / 3; i < n; ++i)
    for (int c = 0; c < 3; ++c) out.pixels[i * 4 + c] = rgb[i * 3 + c];
  return out;
}

}  // namespace glint
