// `glint farm` as a user runs it, against fake sbatch, squeue and scancel that the test writes
// into its own temporary folder and puts first on PATH: each call's arguments are recorded
// (NUL-separated, exactly as received), sbatch prints job ids 1001, 1002, ..., squeue prints the
// file `queue`, and flag files make them fail.
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/run_program.h"
#include "renderer/image.h"
#include "renderer/project_file.h"
#include "renderer/render_options.h"
#include "renderer/render_part.h"
#include "tests/temp_dir.h"

namespace glint::test {

namespace fs = std::filesystem;

inline std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_text_file(const fs::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

class FakeSlurmTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(bin());
    fs::create_directories(calls());
    const std::string c = "'" + calls().string() + "'";
    // Each call: the next number of its program, its arguments recorded, then its answer.
    const std::string record =
        "#!/bin/bash\nprogram=$(basename \"$0\")\nn=$(( $(cat " + c + "/$program-count 2>/dev/null || echo 0) + 1 ))\n"
        "echo $n > " + c + "/$program-count\nprintf '%s\\0' \"$@\" > " + c + "/$program-$n\n";
    fake("sbatch", record +
                       "if [ -e " + c + "/sbatch-fails ] || [ \"$(cat " + c + "/sbatch-fails-at 2>/dev/null)\" = $n ]; then\n"
                       "  echo 'sbatch: error: Batch job submission failed: Invalid partition name specified' >&2\n"
                       "  exit 1\nfi\necho \"$((1000 + n));cluster\"\n");
    fake("squeue", record +
                       "if [ -e " + c + "/squeue-fails ]; then\n"
                       "  echo 'squeue: error: slurm_load_jobs error: Unable to contact slurm controller' >&2\n"
                       "  exit 1\nfi\ncat " + c + "/queue 2>/dev/null || true\n");
    fake("scancel", record);
    const char* path = getenv("PATH");
    original_path_ = path ? path : "";
    setenv("PATH", (bin().string() + ":" + original_path_).c_str(), 1);
    fs::copy_file(fs::path(GLINT_SOURCE_DIR) / "projects" / "cornell_box.glint", project());
  }
  void TearDown() override { setenv("PATH", original_path_.c_str(), 1); }

  void fake(const std::string& name, const std::string& script) {
    write_text_file(bin() / name, script);
    fs::permissions(bin() / name, fs::perms::owner_all);
  }

  fs::path bin() const { return dir / "bin"; }
  fs::path calls() const { return dir / "calls"; }
  fs::path project() const { return dir / "scene.glint"; }
  const std::string& original_path() const { return original_path_; }

  // glint with `args`, stopped after 60 s (a hang is a failure, not a stuck test).
  ProgramResult glint(std::vector<std::string> args) const {
    args.insert(args.begin(), {"timeout", "60", GLINT_EXECUTABLE});
    return run_program(args);
  }

  // The arguments of each call of `program`, in order.
  std::vector<std::vector<std::string>> calls_of(const std::string& program) const {
    std::vector<std::vector<std::string>> all;
    for (int n = 1; fs::exists(calls() / (program + "-" + std::to_string(n))); ++n) {
      const std::string text = read_text(calls() / (program + "-" + std::to_string(n)));
      std::vector<std::string> args;
      for (size_t start = 0; start < text.size();) {
        const size_t end = text.find('\0', start);
        args.push_back(text.substr(start, end - start));
        start = end + 1;
      }
      all.push_back(args);
    }
    return all;
  }

  // A valid part file for part `range` of `project` rendered at width x height (a flat image:
  // only the header matters to glint farm).
  static void write_part(const fs::path& project, const fs::path& file, int width, int height, SampleRange range) {
    Image image;
    image.width = width;
    image.height = height;
    image.pixels.assign(static_cast<size_t>(width) * height * 4, 0.5f);
    for (size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 0;
    fs::create_directories(file.parent_path());
    save_part_image(file, part_info(load_project(project), RenderOptions{}, width, height, range), image);
  }

  TempDir dir;

 private:
  std::string original_path_;
};

}  // namespace glint::test
