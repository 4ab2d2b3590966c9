// farm.json as untrusted input (app/farm_plan.h): every field's type and range checked, with
// the file and the field named; no FIFO, huge file or deep nesting read; job ids and strings
// that go into scripts or command lines checked.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "app/farm_plan.h"
#include "renderer/state_file.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

nlohmann::json good_plan() {
  return {{"project", "/p/scene.glint"}, {"output", "/p/out.exr"}, {"glint", "/usr/bin/glint"},
          {"spp", 16},                   {"parts", 4},              {"partition", ""},
          {"gpus_per_task", 0},          {"job_ids", {"1001"}},     {"merge_job", "1002"},
          {"width", 24}};
}

class FarmPlanFile : public ::testing::Test {
 protected:
  void write(const std::string& text) { std::ofstream(dir / "farm.json") << text; }
  void write(const nlohmann::json& j) { write(j.dump()); }
  void write(const char* text) { write(std::string(text)); }
  // The error read_farm_plan gives for the plan with `field` set to `value`.
  std::string error_with(const std::string& field, const nlohmann::json& value) {
    nlohmann::json j = good_plan();
    if (value.is_discarded()) j.erase(field);
    else j[field] = value;
    write(j);
    return error();
  }
  std::string error() {
    try {
      read_farm_plan(dir.path());
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  }
  std::string file() const { return (dir / "farm.json").string(); }
  test::TempDir dir;
};

TEST_F(FarmPlanFile, RoundTrips) {
  EXPECT_FALSE(read_farm_plan(dir.path()));  // none here
  FarmPlan p;
  p.project = "/a b/it's.glint";
  p.output = "/a b/out.exr";
  p.glint = "/opt/glint";
  p.spp = int64_t(1) << 32;
  p.parts = 100000;
  p.height = 16384;
  p.partition = "gpu,debug";
  p.gpus_per_task = 2;
  p.job_ids = {"1001", "4294967295"};
  p.merge_job = "7";
  write(farm_plan_json(p));
  const auto back = read_farm_plan(dir.path());
  ASSERT_TRUE(back);
  EXPECT_EQ(back->project, p.project);
  EXPECT_EQ(back->spp, p.spp);
  EXPECT_EQ(back->parts, p.parts);
  EXPECT_FALSE(back->width);
  EXPECT_EQ(back->height, 16384);
  EXPECT_EQ(back->partition, p.partition);
  EXPECT_EQ(back->gpus_per_task, 2);
  EXPECT_EQ(back->job_ids, p.job_ids);
  EXPECT_EQ(back->merge_job, "7");
}

TEST_F(FarmPlanFile, JobIdsAreNumbers) {
  EXPECT_EQ(error_with("job_ids", {"1001; touch PWNED #"}),
            file() + ": \"job_ids[0]\": a Slurm job id is a number from 1 to 4294967295, got '1001; touch PWNED #'");
  EXPECT_EQ(error_with("job_ids", {"1001", "$(touch PWNED)"}),
            file() + ": \"job_ids[1]\": a Slurm job id is a number from 1 to 4294967295, got '$(touch PWNED)'");
  EXPECT_EQ(error_with("merge_job", "1002 && touch PWNED"),
            file() + ": \"merge_job\": a Slurm job id is a number from 1 to 4294967295, got '1002 && touch PWNED'");
  EXPECT_EQ(error_with("job_ids", {1001}), file() + ": \"job_ids[0]\": expects a string, got 1001");
  EXPECT_EQ(error_with("job_ids", "1001"), file() + ": \"job_ids\": expects an array of job ids, got \"1001\"");
  EXPECT_EQ(error_with("merge_job", ""), "");
}

TEST_F(FarmPlanFile, BoundsTheJobIds) {
  nlohmann::json ids = nlohmann::json::array();
  for (int i = 0; i < 100000; ++i) ids.push_back(std::to_string(1000 + i));
  EXPECT_EQ(error_with("job_ids", ids), file() + ": \"job_ids\": holds 100000 job ids, more than a plan keeps (1000)");
}

TEST_F(FarmPlanFile, ChecksEachNumbersTypeAndRange) {
  EXPECT_EQ(error_with("parts", 2147483647),
            file() + ": \"parts\": expects an integer from 1 to 16 (at most spp), got 2147483647");
  EXPECT_EQ(error_with("parts", 0), file() + ": \"parts\": expects an integer from 1 to 16 (at most spp), got 0");
  EXPECT_EQ(error_with("parts", 2.5), file() + ": \"parts\": expects an integer from 1 to 16 (at most spp), got 2.5");
  EXPECT_EQ(error_with("spp", "16"), file() + ": \"spp\": expects an integer from 1 to 4294967296, got \"16\"");
  EXPECT_EQ(error_with("spp", 18446744073709551615ull),
            file() + ": \"spp\": expects an integer from 1 to 4294967296, got 18446744073709551615");
  EXPECT_EQ(error_with("spp", -5), file() + ": \"spp\": expects an integer from 1 to 4294967296, got -5");
  EXPECT_EQ(error_with("width", 0), file() + ": \"width\": expects an integer from 1 to 16384, got 0");
  EXPECT_EQ(error_with("height", nullptr), file() + ": \"height\": expects an integer from 1 to 16384, got null");
  EXPECT_EQ(error_with("gpus_per_task", 65), file() + ": \"gpus_per_task\": expects an integer from 0 to 64, got 65");
  EXPECT_EQ(error_with("spp", nlohmann::json::value_t::discarded), file() + ": \"spp\": missing");
  nlohmann::json big = good_plan();
  big["spp"] = 1000000;
  big["parts"] = 100001;
  write(big);
  EXPECT_EQ(error(), file() + ": \"parts\": expects an integer from 1 to 100000, got 100001");
}

TEST_F(FarmPlanFile, StringsHoldOneLineOfAPath) {
  EXPECT_EQ(error_with("project", "/p/x\ntouch PWNED\n.glint"),
            file() + ": \"project\": holds a newline (it would end a line of a Slurm script)");
  EXPECT_EQ(error_with("glint", std::string("/usr/bin/gl\0int", 15)), file() + ": \"glint\": holds a NUL byte");
  EXPECT_EQ(error_with("output", "out.exr"), file() + ": \"output\": expects an absolute path, got 'out.exr'");
  EXPECT_EQ(error_with("output", "/p/out.jpg"), file() + ": \"output\": must end in .png, .hdr or .exr");
  EXPECT_EQ(error_with("project", 7), file() + ": \"project\": expects a string, got 7");
  EXPECT_EQ(error_with("partition", "gpu\n#SBATCH --wrap=x"),
            file() + ": \"partition\": holds a newline (it would end a line of a Slurm script)");
  EXPECT_NE(error_with("partition", "gpu x").find(file() + ": \"partition\": a partition is one or more names"),
            std::string::npos);
}

TEST_F(FarmPlanFile, RefusesWhatIsNoPlan) {
  write("[1, 2]");
  EXPECT_EQ(error(), file() + ": not a farm plan (expects a JSON object)");
  write("{\"project\": ");
  EXPECT_EQ(error().rfind(file() + ": not a farm plan (", 0), 0u) << error();
  write(std::string(100000, '[') + std::string(100000, ']'));
  EXPECT_EQ(error(), file() + ": not a farm plan (nested deeper than a plan)");
}

TEST_F(FarmPlanFile, ReadsNoFifoAndNoHugeFile) {
  ASSERT_EQ(::mkfifo((dir / "farm.json").c_str(), 0600), 0);
  EXPECT_THROW(read_farm_plan(dir.path()), StateFileError);  // at once: never opened for a blocking read
  std::filesystem::remove(dir / "farm.json");
  write(std::string(2 << 20, ' '));
  EXPECT_THROW(read_farm_plan(dir.path()), StateFileError);
}

}  // namespace
}  // namespace glint
