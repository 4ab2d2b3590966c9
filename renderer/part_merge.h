// Merging render parts (docs/DESIGN.md §9) one at a time: a part's pixels are added to per-pixel
// sums in double and dropped, so a merge holds one film's sums and one part whatever the number
// of parts.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "renderer/image.h"
#include "renderer/render_part.h"

namespace glint {

// The sample-weighted mean of the parts added so far: per pixel and channel,
// sum(finite_i * mean_i) / sum(finite_i) in double, finite_i = count_i - discarded_i; alpha is
// the total discarded count. Keeps 32 bytes a pixel.
class PartAccumulator {
 public:
  // Throws std::bad_alloc where the sums do not fit in memory.
  PartAccumulator(int width, int height);
  // Throws PartError (naming part.file) for a part of another size or with an impossible pixel
  // (part_pixel_problem).
  void add(const RenderPart& part);
  Image result() const;

 private:
  int width_ = 0, height_ = 0;
  int64_t samples_ = 0;        // the sum of the added parts' sample counts
  std::vector<double> sums_;   // per pixel: sum(finite_i * mean_i) of r, g, b; sum(discarded_i)
};

// The mean of parts that merge_problems accepts, added in the order of their ranges: the same
// image whatever the order of `parts`.
Image merge_part_images(const std::vector<RenderPart>& parts);

// A merge of part files, or why there is none.
struct MergedParts {
  std::vector<std::string> problems;  // merge_problems of the headers; non-empty: no image
  PartInfo info;                      // the render's: the parts' header with the range 0:N
  Image image;
};

// Reads every header first (read_part_header) and checks the set (merge_problems, with `total`
// as there), then loads the parts one at a time in the order of their ranges and adds them
// (PartAccumulator). Throws ImageError or PartError naming a file that cannot be read, is not a
// part, changed since its header was read or has an impossible pixel, and PartError where the
// merge's sums do not fit in memory.
MergedParts merge_part_files(const std::vector<std::filesystem::path>& files, int64_t total = 0);

}  // namespace glint
