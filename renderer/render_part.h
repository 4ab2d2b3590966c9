// A render in parts (docs/DESIGN.md §9): a sample range A:B of a render is the samples A..B-1 of
// its sequence (RenderOptions::first_sample), saved as an OpenEXR file whose header says which
// render it belongs to. Parts that cover 0..N without gap or overlap merge into the N-sample
// render: the mean of their means weighted by their sample counts.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/image.h"
#include "renderer/render_options.h"
#include "renderer/scene.h"

namespace glint {

class GpuRenderer;

// Samples first..end-1 of a render's sequence.
struct SampleRange {
  int64_t first = 0;
  int64_t end = 0;
  int64_t count() const { return end - first; }
  bool operator==(const SampleRange&) const = default;
};

// "A:B" with 0 <= A < B <= 2^32; nullopt for anything else.
std::optional<SampleRange> parse_sample_range(const std::string& text);
std::string format_sample_range(const SampleRange& range);  // "A:B"

// What a part's header records. Parts merge only if everything but `range` is equal.
struct PartInfo {
  uint64_t digest = 0;  // render_digest: the scene's radiance and the estimator options
  int width = 0, height = 0;
  uint32_t seed = 0;
  SamplerKind sampler = SamplerKind::sobol;
  SampleRange range;
  DisplaySettings display;  // how a merge tonemaps (not in the digest: it never changes radiance)
  bool operator==(const PartInfo&) const = default;
};

// Everything that decides a render's samples besides size, seed, sampler and range: the scene's
// radiance digest (renderer/scene_digest.h: values, and each asset file's size and time) and
// the estimator options that change the samples (renderer/render_option_fields.h). The seed is
// in it too (also recorded on its own, for messages).
uint64_t render_digest(const Scene& scene, const RenderOptions& options);

PartInfo part_info(const Scene& scene, const RenderOptions& options, int width, int height,
                   const SampleRange& range);

// A part file that is not one (no glint header, a bad field): what() names the file and field.
struct PartError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A part as read: its pixels' rgb are the mean of its finite samples, alpha the count of the
// samples it discarded (non-finite), so that a merge weighs each pixel by its finite samples.
// Every rgb value is finite and not negative, every alpha an integer from 0 to the part's
// sample count (part_pixel_problem).
struct RenderPart {
  std::filesystem::path file;
  PartInfo info;
  Image image;
};

// Writes the renderer's accumulation as a part (atomically: a part killed while writing
// leaves no file that a merge could take).
void save_render_part(GpuRenderer& renderer, const PartInfo& info, const std::filesystem::path& file);
void save_part_image(const std::filesystem::path& file, const PartInfo& info, const Image& accumulation);
// Throws ImageError for an unreadable image, PartError for a missing or bad header field, a
// header that is not a part's (part_header_problem: checked before any pixel is decoded), an
// impossible pixel (part_pixel_problem) or too little memory to read it.
RenderPart load_render_part(const std::filesystem::path& file);
// The header alone, checked as load_render_part checks it, without decoding any pixel (for
// `glint farm status`, and a merge's checks before it reads the parts one at a time).
PartInfo read_part_header(const std::filesystem::path& file);

// What makes an OpenEXR header that carries `info` not a part's, or "": a size beyond the
// renderer's film limits (renderer/scene_validation.h: kMaxFilmSide a side, kMaxFilmPixels in
// all), a data window other than 0,0 to width-1,height-1, channels other than A, B, G, R and
// glint.discarded in 32-bit float.
std::string part_header_problem(const PartInfo& info, const ExrHeaderInfo& header);

// The first impossible value of a part's pixels, naming the pixel (x, y) and the channel, or
// "": rgb NaN, infinite or negative; a discarded count (alpha) that is not an integer from 0
// to the part's sample count; an image of another size than its header's.
std::string part_pixel_problem(const RenderPart& part);

// Why a set of parts does not merge into the render of `total` samples (0: up to the largest
// end of any part): parts of another render (naming the file and the field that differs), and
// the missing and overlapping ranges. Empty when they merge.
std::vector<std::string> merge_problems(const std::vector<PartInfo>& parts,
                                        const std::vector<std::filesystem::path>& files,
                                        int64_t total = 0);

}  // namespace glint
