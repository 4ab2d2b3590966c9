// `glint farm status` and `--resume` against fake sbatch/squeue/scancel: farm.json read as
// untrusted input (job ids never reach a shell, every field checked, squeue asked once), parts
// checked against the project as it is now (stale parts resubmitted), removed folders
// recreated, and a failed sbatch that --resume completes.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/farm/farm_test_support.h"

namespace glint::test {
namespace {

class FarmResume : public FakeSlurmTest {
 protected:
  fs::path out() const { return dir / "out.exr"; }
  fs::path farm() const { return dir / "out.farm"; }
  fs::path part(int i) const {
    char name[32];
    std::snprintf(name, sizeof name, "part-%04d.exr", i);
    return farm() / "parts" / name;
  }
  // A farm of `parts` parts of `spp` samples at 8x8, submitted to the fake sbatch (jobs 1001
  // and 1002).
  void submit(int spp, int parts) {
    const ProgramResult r = glint({"farm", "slurm", project().string(), "--spp", std::to_string(spp), "--parts",
                                   std::to_string(parts), "--width", "8", "--height", "8", "-o", out().string()});
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  // Part i of a farm of `parts` parts of `spp` samples, as its task would write it.
  void write_done(int i, int spp, int parts, int width = 8, int height = 8) {
    write_part(project(), part(i), width, height, {int64_t(spp) * i / parts, int64_t(spp) * (i + 1) / parts});
  }
  nlohmann::json plan() const { return nlohmann::json::parse(read_text(farm() / "farm.json")); }
  void set_plan(const nlohmann::json& j) const { write_text_file(farm() / "farm.json", j.dump(2)); }
  ProgramResult status() const { return glint({"farm", "status", "-o", out().string()}); }
  ProgramResult resume(bool dry_run = false) const {
    std::vector<std::string> a = {"farm", "slurm", "-o", out().string(), "--resume"};
    if (dry_run) a.push_back("--dry-run");
    return glint(a);
  }
  static bool has(const ProgramResult& r, const std::string& text) { return r.output.find(text) != std::string::npos; }
};

TEST_F(FarmResume, JobIdsFromTheFileNeverReachAShell) {
  submit(4, 2);
  const std::string pwned = (dir / "PWNED").string();
  nlohmann::json j = plan();
  j["job_ids"] = {"1001; touch " + pwned + " #"};
  set_plan(j);
  for (const ProgramResult& r : {status(), resume(), resume(true)}) {
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_TRUE(has(r, (farm() / "farm.json").string() + ": \"job_ids[0]\": a Slurm job id is a number")) << r.output;
  }
  j = plan();
  j["job_ids"] = {"1001"};
  j["merge_job"] = "1002; touch " + pwned;
  set_plan(j);
  for (const ProgramResult& r : {status(), resume(), resume(true)}) {
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_TRUE(has(r, "\"merge_job\": a Slurm job id is a number")) << r.output;
  }
  EXPECT_FALSE(fs::exists(pwned));
  EXPECT_TRUE(calls_of("squeue").empty());
  EXPECT_TRUE(calls_of("scancel").empty());
}

TEST_F(FarmResume, SqueueIsAskedOnceWithEveryJobAsOneArgument) {
  submit(4, 2);
  nlohmann::json j = plan();
  j["job_ids"] = {"1001", "1003", "1005"};
  j["merge_job"] = "1006";
  set_plan(j);
  write_text_file(dir / "calls" / "queue", "1003_1 RUNNING\n1005_0 PENDING\n1006 PENDING\n");
  const ProgramResult r = status();
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has(r, "part 0  samples 0:2            queued")) << r.output;
  EXPECT_TRUE(has(r, "part 1  samples 2:4            running")) << r.output;
  const auto squeue = calls_of("squeue");
  ASSERT_EQ(squeue.size(), 1u);
  EXPECT_EQ(squeue[0], (std::vector<std::string>{"-h", "-r", "-j", "1001,1003,1005,1006", "-o", "%i %T"}));
}

TEST_F(FarmResume, AnUntrustedPlanIsCheckedFieldByField) {
  submit(4, 2);
  nlohmann::json j = plan();
  j["parts"] = 2147483647;
  set_plan(j);
  ProgramResult r = status();
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has(r, (farm() / "farm.json").string() + ": \"parts\": expects an integer from 1 to 4 (at most spp), got 2147483647"))
      << r.output;
  j = plan();
  j["parts"] = 2;
  nlohmann::json ids = nlohmann::json::array();
  for (int i = 0; i < 100000; ++i) ids.push_back(std::to_string(2000 + i));
  j["job_ids"] = ids;
  write_text_file(farm() / "farm.json", j.dump());  // compact: under farm.json's 1 MiB
  r = status();
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has(r, "\"job_ids\": holds 100000 job ids, more than a plan keeps (1000)")) << r.output;
  EXPECT_TRUE(calls_of("squeue").empty());

  fs::remove(farm() / "farm.json");
  ASSERT_EQ(::mkfifo((farm() / "farm.json").c_str(), 0600), 0);
  r = status();  // at once, not a hang
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has(r, (farm() / "farm.json").string() + ": ")) << r.output;
  EXPECT_TRUE(has(r, "FIFO")) << r.output;
}

TEST_F(FarmResume, AFifoAsAPartIsInvalidNotAHang) {
  submit(4, 2);
  write_done(1, 4, 2);
  ASSERT_EQ(::mkfifo(part(0).c_str(), 0600), 0);
  const ProgramResult r = status();
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has(r, "part 0  samples 0:2            invalid")) << r.output;
  EXPECT_TRUE(has(r, part(0).string() + ": not a regular file")) << r.output;
  EXPECT_TRUE(has(r, "part 1  samples 2:4            done")) << r.output;
}

TEST_F(FarmResume, PartsOfTheProjectAsItWasAreStale) {
  submit(4, 2);
  write_done(0, 4, 2);
  write_done(1, 4, 2);
  ProgramResult r = status();
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(has(r, "2 of 2 parts done, 0 to resubmit")) << r.output;
  r = resume();
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(calls_of("sbatch").size(), 3u);  // the merge only: out.exr is not written
  EXPECT_TRUE(has(r, "submitted the merge (job 1003)")) << r.output;

  // The red wall changes: the scene's digest is not the parts' any more.
  std::string text = read_text(project());
  const std::string red = "[0.65, 0.05, 0.05]";
  ASSERT_NE(text.find(red), std::string::npos);
  text.replace(text.find(red), red.size(), "[0.6, 0.05, 0.05]");
  write_text_file(project(), text);
  r = status();
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has(r, "part 0  samples 0:2            stale")) << r.output;
  EXPECT_TRUE(has(r, part(1).string() + ": stale (its digest (scene, assets and estimator options) is ")) << r.output;
  EXPECT_TRUE(has(r, "0 of 2 parts done, 2 to resubmit")) << r.output;
  r = resume();
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const auto sbatch = calls_of("sbatch");
  ASSERT_EQ(sbatch.size(), 5u);
  EXPECT_EQ(sbatch[3][1], "--array=0-1");
  EXPECT_EQ(sbatch[4][1], "--dependency=afterok:1004");

  // A part of another size (and the seed as the project has it now) names those fields.
  write_done(0, 4, 2);
  write_done(1, 4, 2, 8, 6);
  r = status();
  EXPECT_TRUE(has(r, part(1).string() + ": stale (its size is 8x6, not 8x8 as the project renders now)")) << r.output;
  EXPECT_TRUE(has(r, "1 of 2 parts done")) << r.output;
}

TEST_F(FarmResume, AChangedAssetMakesThePartsStale) {
  fs::copy_file(fs::path(GLINT_SOURCE_DIR) / "projects" / "assets" / "sky.hdr", dir / "sky.hdr");
  std::string text = read_text(project());
  const std::string none = "\"texture\": null";
  ASSERT_NE(text.find(none), std::string::npos);
  text.replace(text.find(none), none.size(), "\"texture\": \"sky.hdr\"");
  write_text_file(project(), text);
  submit(4, 2);
  write_done(0, 4, 2);
  write_done(1, 4, 2);
  EXPECT_EQ(status().exit_code, 0);
  fs::last_write_time(dir / "sky.hdr", fs::last_write_time(dir / "sky.hdr") - std::chrono::hours(24));
  const ProgramResult r = status();
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has(r, part(0).string() + ": stale (its digest")) << r.output;
}

TEST_F(FarmResume, ResumeRecreatesWhatWasRemoved) {
  submit(4, 2);
  for (const char* name : {"parts", "logs", "part.sh", "merge.sh"}) fs::remove_all(farm() / name);
  const ProgramResult r = resume();
  EXPECT_EQ(r.exit_code, 0) << r.output;
  for (const char* name : {"parts", "logs"}) EXPECT_TRUE(fs::is_directory(farm() / name)) << name;
  for (const char* name : {"part.sh", "merge.sh"}) EXPECT_TRUE(fs::is_regular_file(farm() / name)) << name;
  const auto sbatch = calls_of("sbatch");
  ASSERT_EQ(sbatch.size(), 4u);
  EXPECT_EQ(sbatch[2], (std::vector<std::string>{"--parsable", "--array=0-1",
                                                 "--output=" + (farm() / "logs").string() + "/part-%a.log",
                                                 (farm() / "part.sh").string()}));
}

TEST_F(FarmResume, ResumeSubmitsOnlyWhatIsMissingAsRanges) {
  submit(10, 10);
  for (int i : {0, 1, 2, 4, 5, 6}) write_done(i, 10, 10);
  write_text_file(dir / "calls" / "queue", "1001_7 RUNNING\n1001_8 PENDING\n1002 PENDING\n");
  ProgramResult r = resume(true);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(has(r, "scancel 1002\nsbatch --parsable --array=3,9 ")) << r.output;
  EXPECT_EQ(calls_of("sbatch").size(), 2u);  // a dry run submits nothing
  r = resume();
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(calls_of("scancel"), (std::vector<std::vector<std::string>>{{"1002"}}));
  auto sbatch = calls_of("sbatch");
  ASSERT_EQ(sbatch.size(), 4u);
  EXPECT_EQ(sbatch[2][1], "--array=3,9");
  // The merge waits for the new array, and for the old one's tasks still queued.
  EXPECT_EQ(sbatch[3][1], "--dependency=afterok:1003,afterany:1001");
  EXPECT_EQ(plan()["job_ids"], nlohmann::json({"1001", "1003"}));
  EXPECT_EQ(plan()["merge_job"], "1004");

  write_text_file(dir / "calls" / "queue", "");
  r = resume();
  EXPECT_EQ(r.exit_code, 0) << r.output;
  sbatch = calls_of("sbatch");
  ASSERT_EQ(sbatch.size(), 6u);
  EXPECT_EQ(sbatch[4][1], "--array=3,7-9");
  EXPECT_EQ(plan()["job_ids"], nlohmann::json({"1005"}));
}

TEST_F(FarmResume, AnUnknownQueueResubmitsNothing) {
  submit(4, 2);
  write_text_file(dir / "calls" / "squeue-fails", "");
  ProgramResult r = status();
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has(r, "the queue is unknown (squeue failed (exit 1): squeue: error:")) << r.output;
  r = resume();
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has(r, "cannot tell which parts Slurm still has")) << r.output;
  EXPECT_EQ(calls_of("sbatch").size(), 2u);
}

TEST_F(FarmResume, AFailedFirstSubmissionIsResumed) {
  write_text_file(dir / "calls" / "sbatch-fails", "");
  ProgramResult r = glint({"farm", "slurm", project().string(), "--spp", "8", "--parts", "4", "-o", out().string()});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has(r, "Invalid partition name specified")) << r.output;
  EXPECT_TRUE(has(r, "nothing is submitted; the plan is in " + (farm() / "farm.json").string() +
                         ": glint farm slurm -o " + out().string() + " --resume submits what is missing"))
      << r.output;
  EXPECT_EQ(plan()["job_ids"], nlohmann::json::array());
  fs::remove(dir / "calls" / "sbatch-fails");
  r = glint({"farm", "slurm", project().string(), "--spp", "8", "--parts", "4", "-o", out().string()});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has(r, "resume it with --resume")) << r.output;
  r = resume();
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(calls_of("squeue").empty());  // no job to ask about
  const auto sbatch = calls_of("sbatch");
  ASSERT_EQ(sbatch.size(), 3u);
  EXPECT_EQ(sbatch[1][1], "--array=0-3");
  EXPECT_EQ(sbatch[2][1], "--dependency=afterok:1002");
  EXPECT_EQ(plan()["job_ids"], nlohmann::json({"1002"}));
  EXPECT_EQ(plan()["merge_job"], "1003");
}

TEST_F(FarmResume, AFailedMergeSubmissionIsResumed) {
  write_text_file(dir / "calls" / "sbatch-fails-at", "2");
  ProgramResult r = glint({"farm", "slurm", project().string(), "--spp", "8", "--parts", "2", "-o", out().string()});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has(r, "the parts are submitted (job 1001, array 0-1), the merge is not: glint farm slurm -o " +
                         out().string() + " --resume submits it"))
      << r.output;
  EXPECT_EQ(plan()["job_ids"], nlohmann::json({"1001"}));
  write_text_file(dir / "calls" / "queue", "1001_0 RUNNING\n1001_1 PENDING\n");
  r = resume();
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const auto sbatch = calls_of("sbatch");
  ASSERT_EQ(sbatch.size(), 3u);
  EXPECT_EQ(sbatch[2][1], "--dependency=afterany:1001");
  EXPECT_EQ(sbatch[2].back(), (farm() / "merge.sh").string());
  write_text_file(dir / "calls" / "queue", "1001_0 RUNNING\n1001_1 PENDING\n1003 PENDING\n");
  r = resume();
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(has(r, "nothing to resubmit")) << r.output;
  EXPECT_EQ(calls_of("sbatch").size(), 3u);
}

}  // namespace
}  // namespace glint::test
