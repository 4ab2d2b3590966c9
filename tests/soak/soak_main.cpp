// glint-soak: the long headless run of tests/soak/soak.h (bench/reports/SOAK.md). Exit code 0 when every
// check passed, 1 when one failed (each is printed), 2 for bad arguments.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "renderer/gl_context.h"
#include "tests/soak/soak.h"

namespace {

const char* kUsage =
    "usage: glint-soak PROJECT.glint [--frames N] [--size WxH] [--spp K] [--checkpoints C]\n"
    "                  [--warmup N] [--edits N] [--exposure-every M] [--readback-every R]\n"
    "                  [--reference-batches B] [--reference-spp S] [--sigma K] [--paired-spp P]\n"
    "defaults: 100000 frames of 8x8 at 1 spp, 4 checkpoints, 1000 warm-up frames, 10000 edits,\n"
    "exposure every 7 frames, read-back every 1000, reference 1000 x 100 spp, 4 sigma, no pairing\n";

long long number(const char* option, const char* text, long long lo, long long hi) {
  char* end = nullptr;
  long long v = std::strtoll(text, &end, 10);
  if (!text[0] || *end || v < lo || v > hi) {
    std::fprintf(stderr, "glint-soak: %s wants an integer in [%lld, %lld], not '%s'\n", option, lo, hi, text);
    std::exit(2);
  }
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace glint::soak;
  SoakConfig c;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "glint-soak: %s needs a value\n%s", a.c_str(), kUsage);
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (a == "--frames") c.frames = number("--frames", value(), 1, 1 << 24);
    else if (a == "--size") {
      const char* v = value();
      if (std::sscanf(v, "%dx%d", &c.width, &c.height) != 2 || c.width < 2 || c.height < 2 || c.width > 4096 ||
          c.height > 4096) {
        std::fprintf(stderr, "glint-soak: --size wants WxH (2..4096), not '%s'\n", v);
        return 2;
      }
    } else if (a == "--spp") c.spp = static_cast<int>(number("--spp", value(), 1, 1 << 16));
    else if (a == "--checkpoints") c.checkpoints = static_cast<int>(number("--checkpoints", value(), 1, 1000));
    else if (a == "--warmup") c.warmup_frames = number("--warmup", value(), 1, 1 << 24);
    else if (a == "--edits") c.edit_frames = number("--edits", value(), 0, 1 << 24);
    else if (a == "--exposure-every") c.exposure_every = static_cast<int>(number("--exposure-every", value(), 0, 1 << 24));
    else if (a == "--readback-every") c.readback_every = static_cast<int>(number("--readback-every", value(), 0, 1 << 24));
    else if (a == "--reference-batches") c.reference_batches = static_cast<int>(number("--reference-batches", value(), 2, 1 << 20));
    else if (a == "--reference-spp") c.reference_spp = static_cast<int>(number("--reference-spp", value(), 1, 1 << 16));
    else if (a == "--sigma") c.k_sigma = static_cast<double>(number("--sigma", value(), 1, 100));
    else if (a == "--paired-spp") c.paired_spp = static_cast<int>(number("--paired-spp", value(), 0, 1 << 16));
    else if (a.rfind("--", 0) == 0) {
      std::fprintf(stderr, "glint-soak: unknown option %s\n%s", a.c_str(), kUsage);
      return 2;
    } else if (c.project.empty()) c.project = a;
    else {
      std::fprintf(stderr, "glint-soak: one project only\n%s", kUsage);
      return 2;
    }
  }
  if (c.project.empty()) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  try {
    auto context = glint::HeadlessGLContext::create();
    SoakReport rep = run_soak(c, stderr);
    std::fputs(format_report(c, rep).c_str(), stdout);
    auto failed = failures(c, rep);
    for (const std::string& f : failed) std::printf("FAILED: %s\n", f.c_str());
    if (failed.empty()) std::printf("passed: no growth, no drift beyond %.1f standard errors\n", c.k_sigma);
    return failed.empty() ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint-soak: %s\n", e.what());
    return 1;
  }
}
