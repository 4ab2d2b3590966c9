// Which llvmpipe thread goes to which CPU (renderer/llvmpipe_threads.h).
#include <gtest/gtest.h>

#include <cstdlib>

#include "renderer/llvmpipe_threads.h"

namespace glint {
namespace {

TEST(LlvmpipeThreads, IndexOnlyFromLlvmpipeThreadNames) {
  EXPECT_EQ(llvmpipe_thread_index("llvmpipe-0"), 0);
  EXPECT_EQ(llvmpipe_thread_index("llvmpipe-15"), 15);
  EXPECT_EQ(llvmpipe_thread_index("llvmpipe-"), -1);
  EXPECT_EQ(llvmpipe_thread_index("llvmpipe-1a"), -1);
  EXPECT_EQ(llvmpipe_thread_index("llvmpipe-99999999999"), -1);  // no overflow
  EXPECT_EQ(llvmpipe_thread_index("glint"), -1);
  EXPECT_EQ(llvmpipe_thread_index("glint:disk$0"), -1);
  EXPECT_EQ(llvmpipe_thread_index("xllvmpipe-1"), -1);
}

TEST(LlvmpipeThreads, RoundRobinOverTheAllowedCpus) {
  const std::vector<int> allowed = {2, 3, 6};  // e.g. taskset -c 2,3,6
  EXPECT_EQ(cpu_for_llvmpipe_thread(0, allowed), 2);
  EXPECT_EQ(cpu_for_llvmpipe_thread(1, allowed), 3);
  EXPECT_EQ(cpu_for_llvmpipe_thread(2, allowed), 6);
  EXPECT_EQ(cpu_for_llvmpipe_thread(3, allowed), 2);
  EXPECT_EQ(cpu_for_llvmpipe_thread(7, allowed), 3);
  EXPECT_EQ(cpu_for_llvmpipe_thread(0, {}), -1);
  EXPECT_EQ(cpu_for_llvmpipe_thread(-1, allowed), -1);
}

TEST(LlvmpipeThreads, EnvironmentVariableTurnsPinningOff) {
  const char* saved = std::getenv("GLINT_NO_THREAD_PINNING");
  const std::string before = saved ? saved : "";
  unsetenv("GLINT_NO_THREAD_PINNING");
  EXPECT_TRUE(llvmpipe_thread_pinning_enabled());
  setenv("GLINT_NO_THREAD_PINNING", "0", 1);
  EXPECT_TRUE(llvmpipe_thread_pinning_enabled());
  setenv("GLINT_NO_THREAD_PINNING", "", 1);
  EXPECT_TRUE(llvmpipe_thread_pinning_enabled());
  setenv("GLINT_NO_THREAD_PINNING", "1", 1);
  EXPECT_FALSE(llvmpipe_thread_pinning_enabled());
  EXPECT_EQ(pin_llvmpipe_threads().pinned, 0);
  if (saved)
    setenv("GLINT_NO_THREAD_PINNING", before.c_str(), 1);
  else
    unsetenv("GLINT_NO_THREAD_PINNING");
}

}  // namespace
}  // namespace glint
