// A renderer on llvmpipe leaves each of the driver's threads on one CPU of its own, among the
// CPUs this process may use (renderer/llvmpipe_threads.h).
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <sched.h>

#include "renderer/llvmpipe_threads.h"
#include "tests/gl/gl_test_support.h"

namespace glint {
namespace {

std::vector<int> cpus_of(pid_t tid) {
  cpu_set_t mask;
  CPU_ZERO(&mask);
  std::vector<int> cpus;
  if (sched_getaffinity(tid, sizeof mask, &mask) != 0) return cpus;
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
    if (CPU_ISSET(cpu, &mask)) cpus.push_back(cpu);
  return cpus;
}

TEST(GlLlvmpipeThreads, EachThreadOnItsOwnAllowedCpu) {
  test::ensure_gl_context();
  if (!on_llvmpipe()) GTEST_SKIP() << "not llvmpipe: " << gl_renderer_name();
  if (!llvmpipe_thread_pinning_enabled()) GTEST_SKIP() << "GLINT_NO_THREAD_PINNING is set";
  GpuRenderer renderer;  // pins the threads that exist
  const std::vector<int> allowed = cpus_of(0);
  int seen = 0;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
    std::ifstream comm(task.path() / "comm");
    std::string name;
    std::getline(comm, name);
    const int index = llvmpipe_thread_index(name);
    if (index < 0) continue;
    ++seen;
    const std::vector<int> cpus = cpus_of(static_cast<pid_t>(std::stol(task.path().filename().string())));
    if (allowed.size() < 2) {
      EXPECT_EQ(cpus, allowed) << name << " pinned where the process may use one CPU only";
    } else {
      EXPECT_EQ(cpus, std::vector<int>{cpu_for_llvmpipe_thread(index, allowed)}) << name;
    }
  }
  // llvmpipe starts a thread per CPU it may use, none for one CPU (it shades on the caller's).
  if (allowed.size() >= 2 && !std::getenv("LP_NUM_THREADS")) {
    EXPECT_GT(seen, 0) << "no thread named llvmpipe-N in this process";
  }
  const LlvmpipeThreadPinning again = pin_llvmpipe_threads();
  EXPECT_EQ(again.threads, seen);
  EXPECT_EQ(again.pinned, allowed.size() < 2 ? 0 : seen);
}

}  // namespace
}  // namespace glint
