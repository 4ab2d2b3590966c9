#include "renderer/llvmpipe_threads.h"

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#ifdef __linux__
#include <sched.h>
#include <sys/types.h>
#endif

namespace glint {

int llvmpipe_thread_index(const std::string& thread_name) {
  const std::string prefix = "llvmpipe-";
  if (thread_name.size() <= prefix.size() || thread_name.compare(0, prefix.size(), prefix) != 0)
    return -1;
  const std::string digits = thread_name.substr(prefix.size());
  if (digits.size() > 6) return -1;
  for (char c : digits)
    if (!std::isdigit(static_cast<unsigned char>(c))) return -1;
  return std::stoi(digits);
}

int cpu_for_llvmpipe_thread(int index, const std::vector<int>& allowed) {
  if (allowed.empty() || index < 0) return -1;
  return allowed[static_cast<size_t>(index) % allowed.size()];
}

bool llvmpipe_thread_pinning_enabled() {
  const char* off = std::getenv("GLINT_NO_THREAD_PINNING");
  return !(off && *off && std::string(off) != "0");
}

LlvmpipeThreadPinning pin_llvmpipe_threads() {
  LlvmpipeThreadPinning result;
#ifdef __linux__
  if (!llvmpipe_thread_pinning_enabled()) return result;
  cpu_set_t mask;
  CPU_ZERO(&mask);
  if (sched_getaffinity(0, sizeof mask, &mask) != 0) return result;
  std::vector<int> allowed;
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
    if (CPU_ISSET(cpu, &mask)) allowed.push_back(cpu);
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    std::ifstream comm(task.path() / "comm");
    std::string name;
    if (!std::getline(comm, name)) continue;  // the thread has ended
    const int index = llvmpipe_thread_index(name);
    if (index < 0) continue;
    ++result.threads;
    if (allowed.size() < 2) continue;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(cpu_for_llvmpipe_thread(index, allowed), &one);
    const pid_t tid = static_cast<pid_t>(std::atol(task.path().filename().c_str()));
    if (tid > 0 && sched_setaffinity(tid, sizeof one, &one) == 0) ++result.pinned;
  }
#endif
  return result;
}

}  // namespace glint
