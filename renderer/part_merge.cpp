#include "renderer/part_merge.h"

#include <algorithm>
#include <new>
#include <numeric>
#include <optional>
#include <stdexcept>

namespace glint {
namespace {

// Indices of `infos` by the start of their ranges (ranges that merge_problems accepts do not
// overlap, so this is their order in the sample sequence).
std::vector<size_t> range_order(const std::vector<const PartInfo*>& infos) {
  std::vector<size_t> order(infos.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return infos[a]->range.first < infos[b]->range.first; });
  return order;
}

std::string size_text(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

}  // namespace

PartAccumulator::PartAccumulator(int width, int height) : width_(width), height_(height) {
  sums_.assign(size_t(width) * size_t(height) * 4, 0.0);
}

void PartAccumulator::add(const RenderPart& part) {
  if (part.image.width != width_ || part.image.height != height_)
    throw PartError(part.file.string() + ": the image is " + size_text(part.image.width, part.image.height) +
                    ", not the merge's " + size_text(width_, height_));
  if (const std::string problem = part_pixel_problem(part); !problem.empty())
    throw PartError(part.file.string() + ": " + problem);
  const double count = double(part.info.range.count());
  const size_t pixels = size_t(width_) * size_t(height_);
  for (size_t p = 0; p < pixels; ++p) {
    const float* v = &part.image.pixels[p * 4];
    double* sum = &sums_[p * 4];
    sum[3] += v[3];
    const double finite = count - v[3];
    if (finite <= 0) continue;
    for (int c = 0; c < 3; ++c) sum[c] += finite * v[c];
  }
  samples_ += part.info.range.count();
}

Image PartAccumulator::result() const {
  Image out;
  out.width = width_;
  out.height = height_;
  out.pixels.assign(sums_.size(), 0.0f);
  for (size_t p = 0; p < sums_.size(); p += 4) {
    // Counts are integers below 2^33: exact in double.
    const double discarded = sums_[p + 3], finite = double(samples_) - discarded;
    for (int c = 0; c < 3; ++c) out.pixels[p + c] = finite > 0 ? static_cast<float>(sums_[p + c] / finite) : 0.0f;
    out.pixels[p + 3] = static_cast<float>(discarded);
  }
  return out;
}

Image merge_part_images(const std::vector<RenderPart>& parts) {
  if (parts.empty()) throw std::invalid_argument("merge_part_images: no parts");
  std::vector<const PartInfo*> infos;
  for (const RenderPart& part : parts) infos.push_back(&part.info);
  PartAccumulator sums(parts[0].image.width, parts[0].image.height);
  for (size_t i : range_order(infos)) sums.add(parts[i]);
  return sums.result();
}

MergedParts merge_part_files(const std::vector<std::filesystem::path>& files, int64_t total) {
  MergedParts merged;
  std::vector<PartInfo> headers;
  for (const std::filesystem::path& file : files) headers.push_back(read_part_header(file));
  merged.problems = merge_problems(headers, files, total);
  if (!merged.problems.empty()) return merged;
  merged.info = headers[0];
  merged.info.range = {0, 0};
  for (const PartInfo& h : headers) merged.info.range.end = std::max(merged.info.range.end, h.range.end);

  std::vector<const PartInfo*> infos;
  for (const PartInfo& h : headers) infos.push_back(&h);
  const int width = merged.info.width, height = merged.info.height;
  std::optional<PartAccumulator> sums;
  try {
    sums.emplace(width, height);
  } catch (const std::bad_alloc&) {
    throw PartError("not enough memory for the sums of a " + size_text(width, height) + " merge (" +
                    std::to_string((size_t(width) * size_t(height) * 4 * sizeof(double)) >> 20) + " MiB)");
  }
  for (size_t i : range_order(infos)) {
    const RenderPart part = load_render_part(files[i]);
    // A file replaced after its header was read must not slip past merge_problems.
    if (!(part.info == headers[i]))
      throw PartError(files[i].string() + ": changed while the parts were merged (its header is not the one read first)");
    sums->add(part);
  }
  try {
    merged.image = sums->result();
  } catch (const std::bad_alloc&) {
    throw PartError("not enough memory for the merged " + size_text(width, height) + " image");
  }
  return merged;
}

}  // namespace glint
