// run_program (app/run_program.h): an argument vector reaches the program as it is (no shell
// reads it), stdout and stderr come back together with the exit status, and a missing program
// is an error of its own.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "app/run_program.h"
#include "tests/temp_dir.h"

namespace glint {
namespace {

TEST(RunProgram, PassesEachArgumentAsItIs) {
  test::TempDir dir;
  const std::string marker = (dir / "PWNED").string();
  const ProgramResult r =
      run_program({"printf", "[%s]\\n", "a b", "it's", "$(touch " + marker + ")", "; touch " + marker, "%j\\"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.output, "[a b]\n[it's]\n[$(touch " + marker + ")]\n[; touch " + marker + "]\n[%j\\]\n");
  EXPECT_FALSE(std::filesystem::exists(marker));
}

TEST(RunProgram, CapturesBothStreamsAndTheExitStatus) {
  const ProgramResult r = run_program({"bash", "-c", "echo out; echo err >&2; exit 3"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_FALSE(r.signaled);
  EXPECT_EQ(r.output, "out\nerr\n");
}

TEST(RunProgram, ReadsNothingFromStandardInput) {
  // cat of /dev/null ends at once (a terminal or the test's own stdin would block it).
  const ProgramResult r = run_program({"cat"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.output, "");
}

TEST(RunProgram, ReportsASignal) {
  const ProgramResult r = run_program({"bash", "-c", "kill -TERM $$"});
  EXPECT_TRUE(r.signaled);
  EXPECT_EQ(r.exit_code, 128 + 15);
}

TEST(RunProgram, KeepsAtMostTheCapOfTheOutput) {
  const ProgramResult r = run_program({"bash", "-c", "printf %0100000d 0"}, 1000);
  EXPECT_EQ(r.exit_code, 0);  // the rest was read (bash did not die of a closed pipe)
  EXPECT_EQ(r.output.size(), 1000u);
}

TEST(RunProgram, NamesAProgramThatIsNotOnThePath) {
  try {
    run_program({"glint-no-such-program", "x"});
    FAIL() << "no error";
  } catch (const ProgramError& e) {
    EXPECT_TRUE(e.not_found);
    EXPECT_NE(std::string(e.what()).find("glint-no-such-program: cannot run it"), std::string::npos) << e.what();
  }
}

TEST(RunProgram, ShellWordsQuoteWhatAShellWouldRead) {
  EXPECT_EQ(shell_words({"sbatch", "--array=0-3", "--output=/a b/%%x/part-%a.log", "it's"}),
            "sbatch --array=0-3 '--output=/a b/%%x/part-%a.log' 'it'\\''s'");
  EXPECT_EQ(shell_words({"x", ""}), "x ''");
}

}  // namespace
}  // namespace glint
