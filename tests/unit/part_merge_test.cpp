// Merging part files (renderer/part_merge.h): every header checked before any pixel is read,
// the parts then read one at a time (memory of one film whatever their number), forged or
// oversized parts refused with an error naming the file instead of a crash.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "renderer/part_merge.h"
#include "renderer/render_part.h"
#include "tests/part_fixtures.h"
#include "tests/temp_dir.h"

#if defined(__SANITIZE_ADDRESS__)
#define GLINT_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GLINT_ASAN 1
#endif
#endif

namespace glint {
namespace {

namespace fs = std::filesystem;

// AddressSanitizer maps terabytes of shadow memory and keeps freed blocks in quarantine, so
// neither an address-space cap nor a peak RSS means here what it means in a plain build.
#ifdef GLINT_ASAN
#define SKIP_UNDER_ASAN() GTEST_SKIP() << "address-space caps and peak RSS are not meaningful under ASan"
#else
#define SKIP_UNDER_ASAN() (void)0
#endif

PartInfo part(int width, int height, int64_t first, int64_t end) {
  PartInfo p;
  p.digest = 0xabcd;
  p.width = width;
  p.height = height;
  p.seed = 3;
  p.range = {first, end};
  return p;
}

// How a child process ended: what its body returned or threw (what()), and its peak RSS.
struct ChildRun {
  bool exited = false;  // false: killed by a signal (a crash)
  int code = -1;        // 0: the body returned, 1: it threw
  int signal = 0;
  std::string output;
  long max_rss_kib = 0;
};

size_t mapped_bytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmSize:", 0) == 0) return std::stoul(line.substr(7)) * 1024;
  return 0;
}

// Runs `body` in a forked child, with its address space capped at what it has mapped plus
// `headroom` bytes when headroom > 0 (RLIMIT_AS: allocations beyond fail as under a job's
// memory limit), so that a crash or a runaway allocation stays in the child.
ChildRun run_in_child(const std::function<std::string()>& body, size_t headroom = 0) {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) throw std::runtime_error("pipe failed");
  const pid_t pid = fork();
  if (pid == 0) {
    close(pipe_fds[0]);
    if (headroom > 0) {
      const rlimit cap{mapped_bytes() + headroom, mapped_bytes() + headroom};
      setrlimit(RLIMIT_AS, &cap);
    }
    std::string output;
    int code = 0;
    try {
      output = body();
    } catch (const std::exception& e) {
      output = e.what();
      code = 1;
    }
    for (size_t done = 0; done < output.size();) {
      const ssize_t n = write(pipe_fds[1], output.data() + done, output.size() - done);
      if (n <= 0) break;
      done += size_t(n);
    }
    _exit(code);  // no destructors, no gtest: the parent's objects are the parent's
  }
  close(pipe_fds[1]);
  ChildRun run;
  char buffer[4096];
  for (ssize_t n; (n = read(pipe_fds[0], buffer, sizeof buffer)) > 0;) run.output.append(buffer, size_t(n));
  close(pipe_fds[0]);
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  run.exited = WIFEXITED(status);
  run.code = run.exited ? WEXITSTATUS(status) : -1;
  run.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  run.max_rss_kib = usage.ru_maxrss;
  return run;
}

std::string describe(const ChildRun& run) {
  return run.exited ? "exit " + std::to_string(run.code) + ": " + run.output
                    : "killed by signal " + std::to_string(run.signal) + " (" + strsignal(run.signal) + ")";
}

// A part of samples first..end-1 whose values depend on the pixel and the range, with a few
// discarded samples.
Image part_pixels(int width, int height, int64_t first, int64_t end) {
  Image image{width, height, std::vector<float>(size_t(width) * height * 4)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float* v = image.at(x, y);
      for (int c = 0; c < 3; ++c) v[c] = 0.1f * float((x * 7 + y * 3 + c + first) % 11) + 1.0f / float(end);
      v[3] = (x + y + first) % 5 == 0 ? float(std::min<int64_t>(2, end - first)) : 0.0f;
    }
  return image;
}

std::vector<fs::path> write_parts(const test::TempDir& dir, int width, int height, const std::vector<SampleRange>& ranges) {
  std::vector<fs::path> files;
  for (const SampleRange& r : ranges) {
    files.push_back(dir / ("part-" + std::to_string(r.first) + ".exr"));
    save_part_image(files.back(), part(width, height, r.first, r.end), part_pixels(width, height, r.first, r.end));
  }
  return files;
}

TEST(PartMerge, FilesMergeExactlyAsTheSampleWeightedMeanInAnyOrder) {
  test::TempDir dir;
  const std::vector<SampleRange> ranges = {{0, 3}, {3, 10}, {10, 11}, {11, 20}};
  std::vector<fs::path> files = write_parts(dir, 5, 4, ranges);
  const MergedParts merged = merge_part_files(files, 20);
  ASSERT_TRUE(merged.problems.empty());
  EXPECT_EQ(merged.info.range, (SampleRange{0, 20}));
  EXPECT_EQ(merged.info.digest, 0xabcdu);
  // The formula of part_merge.h, in the order of the ranges.
  std::vector<Image> images;
  for (const SampleRange& r : ranges) images.push_back(part_pixels(5, 4, r.first, r.end));
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 5; ++x) {
      double sum[3] = {0, 0, 0}, finite = 0, discarded = 0;
      for (size_t i = 0; i < ranges.size(); ++i) {
        const SampleRange& r = ranges[i];
        const float* v = images[i].at(x, y);
        const double n = double(r.count()) - v[3];
        discarded += v[3];
        finite += n;
        for (int c = 0; c < 3; ++c) sum[c] += n * v[c];
      }
      for (int c = 0; c < 3; ++c) ASSERT_EQ(merged.image.at(x, y)[c], float(sum[c] / finite)) << x << "," << y;
      ASSERT_EQ(merged.image.at(x, y)[3], float(discarded));
    }
  std::reverse(files.begin(), files.end());
  std::swap(files[0], files[2]);
  EXPECT_EQ(merge_part_files(files, 20).image.pixels, merged.image.pixels);
}

// The set is checked on the headers alone: a gap is named even where a part's pixels are
// damaged, and nothing is decoded.
TEST(PartMerge, ChecksTheSetBeforeReadingAnyPixel) {
  test::TempDir dir;
  const std::vector<fs::path> files = write_parts(dir, 32, 32, {{0, 4}, {8, 12}});
  const std::string bytes = test::file_bytes(files[0]);
  test::write_file_bytes(files[0], bytes.substr(0, test::exr_attribute_data(bytes, "") + 16));
  const MergedParts merged = merge_part_files(files);
  ASSERT_EQ(merged.problems.size(), 1u);
  EXPECT_EQ(merged.problems[0], "samples 4:8 are missing (no part has them)");
  EXPECT_TRUE(merged.image.pixels.empty());
}

// A forged part whose header claims 16384x16384 (5 MB of compressed zeros, 5 GiB decoded):
// refused from its header, before tinyexr allocates its pixels, also under a 2 GiB
// address-space cap where tinyexr would write through the null pointers of its failed mallocs.
TEST(PartMerge, AForgedHugePartIsRefusedBeforeItsPixels) {
  SKIP_UNDER_ASAN();
  test::TempDir dir;
  const fs::path forged = dir / "forged.exr";
  test::write_zero_part(forged, part(16384, 16384, 0, 1));
  EXPECT_LT(fs::file_size(forged), 8u << 20);
  const std::string refusal = "forged.exr: its header says 16384x16384, beyond the renderer's film limits";
  const ChildRun load = run_in_child([&] { return std::to_string(load_render_part(forged).image.width); },
                                     size_t(2) << 30);
  ASSERT_TRUE(load.exited && load.code == 1) << describe(load);
  EXPECT_NE(load.output.find(refusal), std::string::npos) << load.output;
  const ChildRun merge = run_in_child([&] { return std::to_string(merge_part_files({forged}).image.width); },
                                      size_t(2) << 30);
  ASSERT_TRUE(merge.exited && merge.code == 1) << describe(merge);
  EXPECT_NE(merge.output.find(refusal), std::string::npos) << merge.output;
  // farm status reads the header alone: the same refusal, in-process.
  try {
    read_part_header(forged);
    ADD_FAILURE() << "no error";
  } catch (const PartError& e) {
    EXPECT_NE(std::string(e.what()).find("beyond the renderer's film limits"), std::string::npos) << e.what();
  }
}

// A part within the limits that does not fit in memory (a 8192x8192 part needs 1.25 GiB to
// decode, the merge 2 GiB of sums): an error naming the file, not a crash or a bare bad_alloc.
TEST(PartMerge, TooLittleMemoryIsAnErrorNamingThePart) {
  SKIP_UNDER_ASAN();
  test::TempDir dir;
  const fs::path big = dir / "big.exr";
  test::write_zero_part(big, part(8192, 8192, 0, 1));
  const ChildRun load = run_in_child([&] { return std::to_string(load_render_part(big).image.width); }, 512u << 20);
  ASSERT_TRUE(load.exited && load.code == 1) << describe(load);
  EXPECT_NE(load.output.find("big.exr: not enough memory to decode its 8192x8192 pixels"), std::string::npos)
      << load.output;
  const ChildRun merge = run_in_child([&] { return std::to_string(merge_part_files({big}).image.width); }, 512u << 20);
  ASSERT_TRUE(merge.exited && merge.code == 1) << describe(merge);
  EXPECT_NE(merge.output.find("not enough memory for the sums of a 8192x8192 merge (2048 MiB)"), std::string::npos)
      << merge.output;
}

// Peak RSS of a merge of 48 parts of 512x512 against one of 2: the parts are read one at a
// time, so the difference is allocator noise. Holding every part (16 bytes a pixel, 4 MiB
// each) would add 46 x 4 = 184 MiB; the bound, 16 MiB (four parts), leaves room for malloc
// keeping freed blocks and for the header list, and is 11 times below that.
TEST(PartMerge, MemoryDoesNotGrowWithTheNumberOfParts) {
  SKIP_UNDER_ASAN();
  test::TempDir dir;
  std::vector<SampleRange> ranges;
  for (int64_t i = 0; i < 48; ++i) ranges.push_back({i, i + 1});
  const std::vector<fs::path> files = write_parts(dir, 512, 512, ranges);
  const std::vector<fs::path> two(files.begin(), files.begin() + 2);
  const auto merge = [](const std::vector<fs::path>& parts) {
    return [parts] { return std::to_string(merge_part_files(parts).image.width); };
  };
  const ChildRun small = run_in_child(merge(two)), large = run_in_child(merge(files));
  ASSERT_TRUE(small.exited && small.code == 0) << describe(small);
  ASSERT_TRUE(large.exited && large.code == 0) << describe(large);
  const long growth_kib = large.max_rss_kib - small.max_rss_kib;
  RecordProperty("peak_rss_2_parts_kib", std::to_string(small.max_rss_kib));
  RecordProperty("peak_rss_48_parts_kib", std::to_string(large.max_rss_kib));
  EXPECT_LT(growth_kib, 16 * 1024) << "2 parts: " << small.max_rss_kib << " KiB, 48 parts: " << large.max_rss_kib
                                   << " KiB";
}

}  // namespace
}  // namespace glint
