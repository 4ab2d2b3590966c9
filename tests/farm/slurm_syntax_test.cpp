// What glint farm writes for Slurm and reads back (app/slurm_syntax.h): job ids, partitions,
// array ranges, literal log paths and squeue's lines.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/slurm_syntax.h"

namespace glint {
namespace {

TEST(SlurmSyntax, JobIdsAreNumbers) {
  for (const char* good : {"1", "1001", "4294967295"}) EXPECT_FALSE(job_id_problem(good)) << good;
  for (const char* bad : {"", "0", "01", "4294967296", "99999999999", "1001; touch PWNED #", "1001_2", " 1",
                          "1\n", "-1", "1001,1002"})
    EXPECT_TRUE(job_id_problem(bad)) << bad;
}

TEST(SlurmSyntax, PartitionsAreNamesSeparatedByCommas) {
  for (const char* good : {"gpu", "gpu,debug", "a.b-c_D9", "x"}) EXPECT_FALSE(partition_problem(good)) << good;
  for (const std::string& bad : std::vector<std::string>{"", "gpu\ntouch PWNED", "a b", "-x", "a,,b", "a,", ",a", "a'b", "a\"b", "a%j",
                                "a\\b", "gpu#x", std::string(65, 'a')})
    EXPECT_TRUE(partition_problem(bad)) << bad;
}

TEST(SlurmSyntax, ArraysAreWrittenAsRanges) {
  std::vector<int> all(30000);
  for (int i = 0; i < 30000; ++i) all[i] = i;
  EXPECT_EQ(array_ranges(all), "0-29999");
  EXPECT_EQ(array_ranges({3, 7, 8, 9}), "3,7-9");
  EXPECT_EQ(array_ranges({0, 1, 5, 10, 11, 12}), "0-1,5,10-12");
  EXPECT_EQ(array_ranges({5}), "5");
  EXPECT_EQ(array_ranges({}), "");
}

TEST(SlurmSyntax, ScatteredIndicesSplitIntoArraysOfBoundedLength) {
  std::vector<int> every_other;
  for (int i = 0; i < 100000; i += 2) every_other.push_back(i);
  ASSERT_GT(array_ranges(every_other).size(), 128u * 1024);  // more than one argument may hold
  const auto groups = split_array(every_other, 16384);
  std::vector<int> joined;
  for (const auto& g : groups) {
    EXPECT_LE(array_ranges(g).size(), 16384u);
    joined.insert(joined.end(), g.begin(), g.end());
  }
  EXPECT_EQ(joined, every_other);
  EXPECT_EQ(split_array({0, 1, 2, 3}, 16384), (std::vector<std::vector<int>>{{0, 1, 2, 3}}));
  EXPECT_TRUE(split_array({}, 16384).empty());
}

TEST(SlurmSyntax, DependenciesListEachKindOnce) {
  EXPECT_EQ(dependency_list({"1003"}, {}), "afterok:1003");
  EXPECT_EQ(dependency_list({"1003", "1004"}, {"1001", "1002"}), "afterok:1003:1004,afterany:1001:1002");
  EXPECT_EQ(dependency_list({}, {"1001"}), "afterany:1001");
  EXPECT_EQ(dependency_list({}, {}), "");
}

TEST(SlurmSyntax, LogPathsAreLiteral) {
  EXPECT_EQ(slurm_filename_literal("/a b/it's/%j%A%%/x"), "/a b/it's/%%j%%A%%%%/x");
  EXPECT_EQ(slurm_filename_literal("/plain/logs"), "/plain/logs");
  EXPECT_FALSE(slurm_filename_literal("/a\\b/logs"));
}

TEST(SlurmSyntax, ReadsSqueueLines) {
  const auto jobs = parse_squeue_lines(
      "1001_3 RUNNING\n1001_[4-6] PENDING\n1002 PENDING\nsqueue: warning: something odd\n1001_x RUNNING\n"
      "1001_2 PENDING extra\n1001_12 COMPLETING\n");
  ASSERT_EQ(jobs.size(), 3u);
  EXPECT_EQ(jobs[0].job, "1001");
  EXPECT_EQ(jobs[0].task, 3);
  EXPECT_EQ(jobs[0].state, "RUNNING");
  EXPECT_EQ(jobs[1].job, "1002");
  EXPECT_EQ(jobs[1].task, -1);
  EXPECT_EQ(jobs[2].task, 12);
  EXPECT_EQ(jobs[2].state, "COMPLETING");
}

}  // namespace
}  // namespace glint
