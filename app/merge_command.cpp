#include "app/merge_command.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "app/command_line.h"
#include "renderer/atomic_file.h"
#include "renderer/image.h"
#include "renderer/part_merge.h"
#include "renderer/render_output.h"
#include "renderer/render_part.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

const char* const kUsage =
    "usage: glint merge PART.exr... -o OUT.{exr,png,hdr} [--spp N]\n"
    "\n"
    "Joins render parts (glint render PROJECT --samples A:B -o PART.exr) into the render of\n"
    "all their samples: per pixel the mean of the parts' means weighted by their sample\n"
    "counts (non-finite samples discarded in a part do not count), the same image as one\n"
    "render of N samples up to float rounding.\n"
    "  -o, --output FILE  .exr: linear radiance, with a part's header for samples 0:N (so it\n"
    "                     can be merged again); .hdr: linear radiance; .png: tonemapped with\n"
    "                     the exposure and tonemap the parts' headers record (the project's\n"
    "                     display settings when they were rendered)\n"
    "  --spp N            the render has N samples: parts must cover exactly 0:N (without it,\n"
    "                     0 up to the largest end of any part)\n"
    "The parts must belong to one render (the same scene digest, size, seed, sampler and\n"
    "display settings) and cover their samples without gap or overlap; otherwise nothing is\n"
    "written and every missing or overlapping range is named. A part whose pixels are not a\n"
    "mean of samples (NaN, infinite or negative radiance, a discarded count that is not an\n"
    "integer from 0 to its sample count) is refused, naming the pixel and channel. The parts\n"
    "are read one at a time: memory holds one image's sums, whatever the number of parts.\n"
    "Exit codes: 0 merged, 1 the parts do not make one render (or a file could not be read or\n"
    "written), 2 bad arguments.\n";

struct Options {
  std::vector<std::string> parts;
  std::string output;
  int64_t total = 0;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError{a + " needs a value"};
      return argv[++i];
    };
    if (a == "-o" || a == "--output") {
      o.output = value();
    } else if (a == "--spp") {
      const std::string v = value();
      const auto range = parse_sample_range("0:" + v);
      if (!range) throw UsageError{"--spp expects an integer from 1 to 4294967296, got '" + v + "'"};
      o.total = range->end;
    } else if (!a.empty() && a[0] == '-') {
      throw UsageError{"unknown option " + a};
    } else {
      o.parts.push_back(a);
    }
  }
  if (o.parts.empty()) throw UsageError{"no parts given"};
  if (o.output.empty()) throw UsageError{"no output file given (-o OUT.exr|.png|.hdr)"};
  if (const auto problem = output_format_problem(o.output))
    throw UsageError{"output '" + o.output + "' " + *problem};
  for (const std::string& part : o.parts) {
    std::error_code ec;
    if (part == o.output || (fs::exists(part, ec) && fs::exists(o.output, ec) && fs::equivalent(part, o.output, ec)))
      throw UsageError{"-o " + o.output + " is one of the parts: it would be overwritten"};
  }
  return o;
}

}  // namespace

int run_merge_command(int argc, char** argv) {
  Options o;
  if (int code = parse_command_line("glint merge", kUsage, argc, argv, parse, o); code >= 0) return code;
  try {
    if (const auto problem = file_write_problem(o.output)) throw std::runtime_error(o.output + ": " + *problem);
    const MergedParts merged = merge_part_files(std::vector<fs::path>(o.parts.begin(), o.parts.end()), o.total);
    if (!merged.problems.empty()) {
      std::fprintf(stderr, "glint merge: the %zu parts do not make one render; nothing written:\n", o.parts.size());
      for (const std::string& p : merged.problems) std::fprintf(stderr, "  %s\n", p.c_str());
      return 1;
    }
    const std::string ext = fs::path(o.output).extension().string();
    try {
      if (ext == ".exr") {
        save_part_image(o.output, merged.info, merged.image);
      } else if (ext == ".png") {
        save_image(o.output, tonemapped(merged.image, merged.info.display));
      } else {
        Image opaque = merged.image;
        for (size_t i = 3; i < opaque.pixels.size(); i += 4) opaque.pixels[i] = 1.0f;
        save_image(o.output, opaque);
      }
    } catch (const std::bad_alloc&) {
      throw std::runtime_error(o.output + ": not enough memory to encode the " + std::to_string(merged.image.width) +
                               "x" + std::to_string(merged.image.height) + " image; nothing written");
    }
    std::fprintf(stderr, "glint merge: wrote %s (%dx%d, %zu parts, samples 0:%lld)\n", o.output.c_str(),
                 merged.image.width, merged.image.height, o.parts.size(),
                 static_cast<long long>(merged.info.range.end));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint merge: %s\n", e.what());
    return 1;
  }
}

}  // namespace glint
