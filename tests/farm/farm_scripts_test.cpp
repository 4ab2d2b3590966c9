// `glint farm slurm` writes scripts and sbatch command lines that hold any path as it is: no
// path goes into an #SBATCH directive (the log files are sbatch arguments, '%' escaped as
// Slurm's filename patterns need), a newline or an unsafe partition is refused, and the real
// sbatch, where installed, parses what glint gives it. Fake sbatch/squeue/scancel record the calls.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "app/run_program.h"
#include "tests/farm/farm_test_support.h"

namespace glint::test {
namespace {

std::string escaped_percent(const std::string& path) {
  std::string s;
  for (char c : path) s += c == '%' ? std::string("%%") : std::string(1, c);
  return s;
}

// The argv the script's `exec` line would run for array task `task` (exec replaced by a
// function that prints its arguments, one per line).
std::vector<std::string> exec_of(const fs::path& script, const std::string& task) {
  const ProgramResult r = run_program({"env", "SLURM_ARRAY_TASK_ID=" + task, "bash", "-c",
                                       "exec() { printf '%s\\n' \"$@\"; exit 0; }; source \"$0\"", script.string()});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  std::vector<std::string> lines;
  std::istringstream in(r.output);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The sbatch of the machine (not the fake), or empty where Slurm is not installed.
std::string real_sbatch(const std::string& path) {
  std::istringstream dirs(path);
  for (std::string d; std::getline(dirs, d, ':');)
    if (!d.empty() && ::access((fs::path(d) / "sbatch").c_str(), X_OK) == 0) return (fs::path(d) / "sbatch").string();
  return "";
}

class FarmScripts : public FakeSlurmTest {};

TEST_F(FarmScripts, ANewlineInAPathOrThePartitionIsRefused) {
  // Each would end an #SBATCH line, and "touch PWNED" would run in every job.
  const fs::path work = dir / "work";
  fs::create_directories(work);
  const std::string newline_project = (dir / "scene\ntouch PWNED\n.glint").string();
  fs::copy_file(project(), newline_project);
  const std::string spp_parts[] = {"--spp", "4", "--parts", "2"};
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{project().string(), "-o", (work / "x\ntouch PWNED\n.exr").string()}, "-o holds a newline"},
      {{project().string(), "-o", (work / "out.exr").string(), "--partition", "gpu\ntouch PWNED"},
       "--partition 'gpu\ntouch PWNED': a partition is one or more names"},
      {{project().string(), "-o", (work / "out.exr").string(), "--partition", "gpu --wrap=x"},
       "a partition is one or more names"},
      {{newline_project, "-o", (work / "out.exr").string()}, "the project path holds a newline"},
  };
  for (Case c : cases) {
    c.args.insert(c.args.begin(), {"farm", "slurm"});
    c.args.insert(c.args.end(), std::begin(spp_parts), std::end(spp_parts));
    const ProgramResult r = glint(c.args);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << r.output;
  }
  // Whatever was submitted, run as Slurm runs it (from the folder, as a task of no part),
  // touches nothing.
  for (const auto& call : calls_of("sbatch"))
    run_program({"bash", "-c", "cd \"$0\" && SLURM_ARRAY_TASK_ID=99999 bash \"$1\"", work.string(), call.back()});
  EXPECT_FALSE(fs::exists(work / "PWNED"));
  EXPECT_TRUE(calls_of("sbatch").empty());
  EXPECT_TRUE(fs::is_empty(work));  // no farm folder
}

TEST_F(FarmScripts, PathsWithSpacesQuotesAndPercentReachSlurmAsTheyAre) {
  const fs::path folder = dir / "a b'c\"d%j%a\\x";
  const fs::path out_folder = dir / "renders 'final' \"v2\" 100%";
  fs::create_directories(folder);
  fs::create_directories(out_folder);
  // A backslash in the farm folder is refused (Slurm drops it from log names); elsewhere it is kept.
  const fs::path project_there = folder / "scene.glint";
  fs::copy_file(project(), project_there);
  const fs::path out = out_folder / "out.exr", farm = out_folder / "out.farm";
  const ProgramResult r = glint({"farm", "slurm", project_there.string(), "--spp", "16", "--parts", "2", "--width",
                                 "8", "--height", "6", "-o", out.string(), "--partition", "gpu,debug",
                                 "--gpus-per-task", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto sbatch = calls_of("sbatch");
  ASSERT_EQ(sbatch.size(), 2u);
  const std::string logs = escaped_percent((farm / "logs").string());
  EXPECT_EQ(sbatch[0], (std::vector<std::string>{"--parsable", "--array=0-1", "--output=" + logs + "/part-%a.log",
                                                 (farm / "part.sh").string()}));
  EXPECT_EQ(sbatch[1], (std::vector<std::string>{"--parsable", "--dependency=afterok:1001",
                                                 "--output=" + logs + "/merge.log", (farm / "merge.sh").string()}));
  // The directives hold no path: fixed words, numbers and the checked partition.
  const std::regex directive("#SBATCH --(job-name=glint-(part|merge)|ntasks=1|array=0-1|partition=gpu,debug|gpus-per-task=1)");
  for (const char* script : {"part.sh", "merge.sh"}) {
    std::istringstream lines(read_text(farm / script));
    for (std::string line; std::getline(lines, line);)
      if (line.rfind("#SBATCH", 0) == 0) {
        EXPECT_TRUE(std::regex_match(line, directive)) << script << ": " << line;
      }
    const ProgramResult syntax = run_program({"bash", "-n", (farm / script).string()});
    EXPECT_EQ(syntax.exit_code, 0) << script << ": " << syntax.output;
  }
  // Each task runs its part with every path as one argument.
  const std::string glint_path = fs::canonical(GLINT_EXECUTABLE).string();
  const std::string project_path = fs::canonical(project_there).string();
  EXPECT_EQ(exec_of(farm / "part.sh", "1"),
            (std::vector<std::string>{glint_path, "render", project_path, "--samples", "8:16", "-o",
                                      (farm / "parts" / "part-0001.exr").string(), "--width", "8", "--height", "6"}));
  EXPECT_EQ(exec_of(farm / "part.sh", "0")[4], "0:8");
  for (const char* task : {"2", "-1", "01", "1; touch x", ""}) {
    const ProgramResult none = run_program({"env", "SLURM_ARRAY_TASK_ID=" + std::string(task), "bash",
                                            (farm / "part.sh").string()});
    EXPECT_EQ(none.exit_code, 2) << task;
    EXPECT_NE(none.output.find("glint farm: no part '" + std::string(task) + "'"), std::string::npos) << none.output;
  }
  write_text_file(farm / "parts" / "part-0000.exr", "");
  write_text_file(farm / "parts" / "part-0001.exr", "");
  EXPECT_EQ(exec_of(farm / "merge.sh", ""),
            (std::vector<std::string>{glint_path, "merge", "--spp", "16", (farm / "parts" / "part-0000.exr").string(),
                                      (farm / "parts" / "part-0001.exr").string(), "-o",
                                      fs::weakly_canonical(out).string()}));
}

TEST_F(FarmScripts, AFarmFolderWithABackslashIsRefused) {
  fs::create_directories(dir / "a\\b");
  const ProgramResult r = glint({"farm", "slurm", project().string(), "--spp", "4", "--parts", "2", "-o",
                                 (dir / "a\\b" / "out.exr").string()});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("holds a backslash (Slurm's log file names cannot"), std::string::npos) << r.output;
}

// The real sbatch reads a script's #SBATCH lines before it asks the controller: with a
// configuration whose controller cannot be reached (port 1, one-second timeout), a script it
// accepts fails with "Unable to contact slurm controller", a bad directive with its own error.
TEST_F(FarmScripts, TheRealSbatchParsesWhatGlintSubmits) {
  const std::string sbatch = real_sbatch(original_path() + ":/usr/bin:/usr/local/bin");
  if (sbatch.empty()) GTEST_SKIP() << "sbatch is not installed (scripts/setup.sh installs slurm-client)";
  write_text_file(dir / "slurm.conf",
                  "ClusterName=glinttest\nSlurmctldHost=localhost(127.0.0.1)\nSlurmctldPort=1\nMessageTimeout=1\n"
                  "SelectType=select/cons_tres\nGresTypes=gpu\n"
                  "NodeName=n NodeAddr=127.0.0.1 CPUs=1\nPartitionName=gpu Nodes=n Default=YES\n");
  const char* old_conf = getenv("SLURM_CONF");
  const std::string saved = old_conf ? old_conf : "";
  setenv("SLURM_CONF", (dir / "slurm.conf").c_str(), 1);
  auto run_sbatch = [&](std::vector<std::string> args) {
    args.insert(args.begin(), sbatch);
    return run_program(args).output;
  };
  // The check tells a bad directive from a good one.
  write_text_file(dir / "bad.sh", "#!/bin/bash\n#SBATCH --output=/a b/x.log\ntrue\n");
  write_text_file(dir / "good.sh", "#!/bin/bash\n#SBATCH --output=\"/a b/x.log\"\ntrue\n");
  EXPECT_NE(run_sbatch({"--parsable", (dir / "bad.sh").string()}).find("Invalid directive"), std::string::npos);
  EXPECT_NE(run_sbatch({"--parsable", (dir / "good.sh").string()}).find("Unable to contact slurm controller"),
            std::string::npos);

  const fs::path out_folder = dir / "a b'c\"d %j %% 'x";
  fs::create_directories(out_folder);
  const ProgramResult r = glint({"farm", "slurm", project().string(), "--spp", "16", "--parts", "4", "-o",
                                 (out_folder / "out.exr").string(), "--partition", "gpu", "--gpus-per-task", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto calls = calls_of("sbatch");
  ASSERT_EQ(calls.size(), 2u);
  for (const auto& call : calls) {
    const std::string answer = run_sbatch(call);
    EXPECT_NE(answer.find("Unable to contact slurm controller"), std::string::npos) << answer;
    EXPECT_EQ(answer.find("Invalid directive"), std::string::npos) << answer;
    EXPECT_EQ(answer.find("Unmatched"), std::string::npos) << answer;
  }
  if (old_conf) setenv("SLURM_CONF", saved.c_str(), 1);
  else unsetenv("SLURM_CONF");
}

TEST_F(FarmScripts, ManyPartsAreOneRangeAndAScriptOfAFewLines) {
  const ProgramResult r = glint({"farm", "slurm", project().string(), "--spp", "30000", "--parts", "30000", "-o",
                                 (dir / "out.exr").string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto sbatch = calls_of("sbatch");
  ASSERT_EQ(sbatch.size(), 2u);
  EXPECT_EQ(sbatch[0][1], "--array=0-29999");
  EXPECT_LT(fs::file_size(dir / "out.farm" / "part.sh"), 2000u);
  EXPECT_EQ(exec_of(dir / "out.farm" / "part.sh", "29999")[4], "29999:30000");
  EXPECT_NE(r.output.find("submitted 30000 parts (job 1001, array 0-29999) and the merge (job 1002)"),
            std::string::npos) << r.output;
}

TEST_F(FarmScripts, ADryRunPrintsTheScriptsThePartsAndTheCommands) {
  const ProgramResult r = glint({"farm", "slurm", project().string(), "--spp", "12", "--parts", "4", "--width", "8",
                                 "-o", (dir / "out.exr").string(), "--dry-run"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("# part 2: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--samples 6:9 -o " + (dir / "out.farm" / "parts" / "part-0002.exr").string() + " --width 8"),
            std::string::npos) << r.output;
  EXPECT_NE(r.output.find("sbatch --parsable --array=0-3 --output=" + (dir / "out.farm" / "logs").string() + "/part-%a.log"),
            std::string::npos) << r.output;
  EXPECT_TRUE(calls_of("sbatch").empty());
  EXPECT_FALSE(fs::exists(dir / "out.farm"));
}

}  // namespace
}  // namespace glint::test
