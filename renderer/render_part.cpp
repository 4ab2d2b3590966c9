#include "renderer/render_part.h"

#include <algorithm>
#include <cerrno>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numeric>
#include <type_traits>

#include "renderer/gpu_renderer.h"
#include "renderer/render_option_fields.h"
#include "renderer/scene_digest.h"
#include "renderer/scene_validation.h"

namespace glint {
namespace {

// The OpenEXR header fields of a part (string attributes) and the channel of its discarded
// counts (alpha of the accumulation, see RenderPart).
constexpr const char* kDigest = "glint.digest";
constexpr const char* kWidth = "glint.width";
constexpr const char* kHeight = "glint.height";
constexpr const char* kSeed = "glint.seed";
constexpr const char* kSampler = "glint.sampler";
constexpr const char* kSamples = "glint.samples";
constexpr const char* kExposure = "glint.exposure";
constexpr const char* kTonemap = "glint.tonemap";
constexpr const char* kDiscardedChannel = "glint.discarded";

constexpr int64_t kMaxSample = int64_t(1) << 32;  // the shader's sample index is a uint

std::string hex64(uint64_t v) {
  char text[17];
  std::snprintf(text, sizeof text, "%016" PRIx64, v);
  return text;
}

const char* sampler_name(SamplerKind s) { return s == SamplerKind::sobol ? "sobol" : "pcg"; }

ExrAttributes attributes_of(const PartInfo& p) {
  char exposure[32];
  std::snprintf(exposure, sizeof exposure, "%.9g", p.display.exposure);
  return {{kDigest, hex64(p.digest)},
          {kWidth, std::to_string(p.width)},
          {kHeight, std::to_string(p.height)},
          {kSeed, std::to_string(p.seed)},
          {kSampler, sampler_name(p.sampler)},
          {kSamples, format_sample_range(p.range)},
          {kExposure, exposure},
          {kTonemap, p.display.tonemap == Tonemap::filmic ? "filmic" : "linear"}};
}

// An unsigned integer field of at most `max`.
uint64_t parse_unsigned(const std::filesystem::path& file, const char* field, const std::string& text,
                        uint64_t max, int base = 10) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(text.c_str(), &end, base);
  if (text.empty() || text[0] == '-' || *end != '\0' || errno != 0 || v > max)
    throw PartError(file.string() + ": header field " + field + " is not valid ('" + text + "')");
  return v;
}

PartInfo info_from(const std::filesystem::path& file, const ExrAttributes& attributes) {
  std::map<std::string, std::string> fields(attributes.begin(), attributes.end());
  auto field = [&](const char* name) -> const std::string& {
    auto it = fields.find(name);
    if (it == fields.end())
      throw PartError(file.string() + ": not a glint render part (no " + name +
                      " in its header; render parts with glint render --samples A:B)");
    return it->second;
  };
  PartInfo p;
  p.digest = parse_unsigned(file, kDigest, field(kDigest), UINT64_MAX, 16);
  p.width = static_cast<int>(parse_unsigned(file, kWidth, field(kWidth), kMaxFilmSide));
  p.height = static_cast<int>(parse_unsigned(file, kHeight, field(kHeight), kMaxFilmSide));
  p.seed = static_cast<uint32_t>(parse_unsigned(file, kSeed, field(kSeed), UINT32_MAX));
  const std::string& sampler = field(kSampler);
  if (sampler == "sobol") p.sampler = SamplerKind::sobol;
  else if (sampler == "pcg") p.sampler = SamplerKind::pcg;
  else throw PartError(file.string() + ": header field " + kSampler + " is not valid ('" + sampler + "')");
  const auto range = parse_sample_range(field(kSamples));
  if (!range) throw PartError(file.string() + ": header field " + kSamples + " is not valid ('" + field(kSamples) + "')");
  p.range = *range;
  const std::string& exposure = field(kExposure);
  char* end = nullptr;
  p.display.exposure = std::strtof(exposure.c_str(), &end);
  if (exposure.empty() || *end != '\0' || !std::isfinite(p.display.exposure))
    throw PartError(file.string() + ": header field " + kExposure + " is not valid ('" + exposure + "')");
  const std::string& tonemap = field(kTonemap);
  if (tonemap == "filmic") p.display.tonemap = Tonemap::filmic;
  else if (tonemap == "linear") p.display.tonemap = Tonemap::linear;
  else throw PartError(file.string() + ": header field " + kTonemap + " is not valid ('" + tonemap + "')");
  return p;
}

}  // namespace

std::optional<SampleRange> parse_sample_range(const std::string& text) {
  const size_t colon = text.find(':');
  if (colon == std::string::npos) return std::nullopt;
  auto number = [](const std::string& s) -> std::optional<int64_t> {
    if (s.empty() || s.size() > 12 || s.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
    return std::stoll(s);
  };
  const auto a = number(text.substr(0, colon)), b = number(text.substr(colon + 1));
  if (!a || !b || *a >= *b || *b > kMaxSample) return std::nullopt;
  return SampleRange{*a, *b};
}

std::string format_sample_range(const SampleRange& r) {
  return std::to_string(r.first) + ":" + std::to_string(r.end);
}

uint64_t render_digest(const Scene& scene, const RenderOptions& options) {
  Hasher h;
  h.value(digest_scene(scene).radiance());
  // The options that change the samples (render_option_fields.h); bools and enums as ints.
  visit_render_option_fields([&](const auto& f) {
    if (!f.in_digest()) return;
    const auto& value = options.*f.member;
    using M = std::decay_t<decltype(value)>;
    if constexpr (std::is_same_v<M, bool> || std::is_enum_v<M>) h.value(static_cast<int>(value));
    else h.value(value);
  });
  return h.result();
}

PartInfo part_info(const Scene& scene, const RenderOptions& options, int width, int height,
                   const SampleRange& range) {
  PartInfo p;
  p.digest = render_digest(scene, options);
  p.width = width;
  p.height = height;
  p.seed = scene.render.seed;
  p.sampler = options.sampler;
  p.range = range;
  p.display = scene.display;
  return p;
}

void save_part_image(const std::filesystem::path& file, const PartInfo& info, const Image& accumulation) {
  save_exr(file, accumulation, attributes_of(info), kDiscardedChannel);
}

void save_render_part(GpuRenderer& renderer, const PartInfo& info, const std::filesystem::path& file) {
  save_part_image(file, info, renderer.read_accumulation());
}

std::string part_header_problem(const PartInfo& info, const ExrHeaderInfo& header) {
  const std::string size = std::to_string(info.width) + "x" + std::to_string(info.height);
  if (info.width < 1 || info.height < 1 || int64_t(info.width) * info.height > kMaxFilmPixels)
    return "its header says " + size + ", beyond the renderer's film limits (1 to " + std::to_string(kMaxFilmSide) +
           " pixels a side, " + std::to_string(kMaxFilmPixels) + " in all)";
  if (header.min_x != 0 || header.min_y != 0 || header.width != info.width || header.height != info.height)
    return "its pixels are " + std::to_string(header.width) + "x" + std::to_string(header.height) + " at (" +
           std::to_string(header.min_x) + ", " + std::to_string(header.min_y) + ") but its header says " + size +
           " at (0, 0)";
  std::vector<std::string> channels;
  bool all_float = true;
  for (const ExrChannel& c : header.channels) {
    channels.push_back(c.name);
    all_float = all_float && c.type == ExrPixelType::float32;
  }
  std::sort(channels.begin(), channels.end());
  if (channels != std::vector<std::string>{"A", "B", "G", "R", kDiscardedChannel} || !all_float) {
    std::string list;
    for (const ExrChannel& c : header.channels)
      list += (list.empty() ? "" : ", ") + c.name.substr(0, 32) +
              (c.type == ExrPixelType::float32 ? "" : c.type == ExrPixelType::half ? " (half)" : " (uint)");
    if (header.channels.size() > 8) list = std::to_string(header.channels.size()) + " channels";
    return "its channels are " + list + "; a part has A, B, G, R and " + kDiscardedChannel + ", all 32-bit float";
  }
  return "";
}

std::string part_pixel_problem(const RenderPart& part) {
  const Image& image = part.image;
  if (image.width != part.info.width || image.height != part.info.height ||
      image.pixels.size() != size_t(image.width) * size_t(image.height) * 4)
    return "the image is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
           " but its header says " + std::to_string(part.info.width) + "x" + std::to_string(part.info.height);
  const double samples = double(part.info.range.count());
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const float v = image.pixels[i];
    const bool radiance = i % 4 < 3;
    if (std::isfinite(v) && v >= 0 && (radiance || (v == std::floor(v) && v <= samples))) continue;
    const size_t pixel = i / 4;
    char text[256];
    if (radiance)
      std::snprintf(text, sizeof text, "pixel (%zu, %zu) channel %c is %.9g (radiance must be finite and not negative)",
                    pixel % size_t(image.width), pixel / size_t(image.width), "RGB"[i % 4], double(v));
    else
      std::snprintf(text, sizeof text,
                    "pixel (%zu, %zu) channel %s is %.9g (a count of discarded samples: an integer from 0 to the "
                    "part's %lld samples)",
                    pixel % size_t(image.width), pixel / size_t(image.width), kDiscardedChannel, double(v),
                    static_cast<long long>(part.info.range.count()));
    return text;
  }
  return "";
}

RenderPart load_render_part(const std::filesystem::path& file) {
  PartInfo info;
  // The header is checked before tinyexr decodes (and allocates) any pixel.
  const auto check_header = [&](const ExrHeaderInfo& header) {
    info = info_from(file, header.attributes);
    if (const std::string problem = part_header_problem(info, header); !problem.empty())
      throw PartError(file.string() + ": " + problem);
  };
  try {
    RenderPart part{file, {}, load_exr_with_attributes(file, kDiscardedChannel, check_header).image};
    part.info = info;
    if (const std::string problem = part_pixel_problem(part); !problem.empty())
      throw PartError(file.string() + ": " + problem);
    return part;
  } catch (const std::bad_alloc&) {
    const std::string size = std::to_string(info.width) + "x" + std::to_string(info.height) + " ";
    throw PartError(file.string() + ": not enough memory to read its " + (info.width > 0 ? size : "") + "pixels");
  }
}

PartInfo read_part_header(const std::filesystem::path& file) {
  const ExrHeaderInfo header = read_exr_header(file);
  const PartInfo info = info_from(file, header.attributes);
  if (const std::string problem = part_header_problem(info, header); !problem.empty())
    throw PartError(file.string() + ": " + problem);
  return info;
}

std::vector<std::string> merge_problems(const std::vector<PartInfo>& parts,
                                        const std::vector<std::filesystem::path>& files,
                                        int64_t total) {
  std::vector<std::string> problems;
  if (parts.empty()) return {"no parts given"};
  const PartInfo& a = parts[0];
  const std::string first = files[0].string();
  for (size_t i = 1; i < parts.size(); ++i) {
    const PartInfo& b = parts[i];
    auto differs = [&](const std::string& what, const std::string& x, const std::string& y) {
      problems.push_back(files[i].string() + " is not part of the render of " + first + ": its " + what +
                         " is " + y + ", not " + x);
    };
    if (b.digest != a.digest) differs("digest (scene, assets and estimator options)", hex64(a.digest), hex64(b.digest));
    if (b.width != a.width || b.height != a.height)
      differs("size", std::to_string(a.width) + "x" + std::to_string(a.height),
              std::to_string(b.width) + "x" + std::to_string(b.height));
    if (b.seed != a.seed) differs("seed", std::to_string(a.seed), std::to_string(b.seed));
    if (b.sampler != a.sampler) differs("sampler", sampler_name(a.sampler), sampler_name(b.sampler));
    if (!(b.display == a.display)) differs("display settings (exposure, tonemap)",
                                           attributes_of(a)[6].second + " " + attributes_of(a)[7].second,
                                           attributes_of(b)[6].second + " " + attributes_of(b)[7].second);
  }
  std::vector<size_t> order(parts.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t x, size_t y) {
    return parts[x].range.first != parts[y].range.first ? parts[x].range.first < parts[y].range.first
                                                        : parts[x].range.end < parts[y].range.end;
  });
  int64_t covered = 0;  // samples 0..covered-1 are in some part
  size_t covering = order[0];
  for (size_t i : order) {
    const SampleRange& r = parts[i].range;
    if (r.first > covered)
      problems.push_back("samples " + format_sample_range({covered, r.first}) + " are missing (no part has them)");
    else if (r.first < covered)
      problems.push_back("samples " + format_sample_range({r.first, std::min(covered, r.end)}) + " overlap: in both " +
                         files[covering].string() + " and " + files[i].string());
    if (r.end > covered) {
      covered = r.end;
      covering = i;
    }
  }
  if (total > 0 && covered < total)
    problems.push_back("samples " + format_sample_range({covered, total}) + " are missing (no part has them)");
  if (total > 0 && covered > total)
    problems.push_back(files[covering].string() + " has samples up to " + std::to_string(covered) +
                       ", beyond the " + std::to_string(total) + " asked for");
  return problems;
}

}  // namespace glint
