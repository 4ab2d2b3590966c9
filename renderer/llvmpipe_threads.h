// Where Mesa's llvmpipe runs its rasterizer threads. llvmpipe shades a draw on threads of its
// own ("llvmpipe-0", "llvmpipe-1", ..., one per CPU by default), which sleep between draws. Once
// they had slept for a while (10 ms sufficed on the development machine), a draw often started
// with two of them on one CPU while another CPU stayed idle (Linux wakes a thread near the thread
// that wakes it), and a draw of a few milliseconds then took as long as on one thread
// (bench/reports/THROUGHPUT.md, "Short passes and llvmpipe's threads"). Pinning thread k to the k-th CPU
// that this process may use keeps them apart. Linux only; elsewhere nothing is done.
#pragma once

#include <string>
#include <vector>

namespace glint {

// "llvmpipe-3" -> 3; any other thread name -> -1.
int llvmpipe_thread_index(const std::string& thread_name);

// The CPU for llvmpipe thread `index` among the CPUs `allowed` (in the order given): round
// robin, so that threads beyond the CPU count share them evenly. -1 when `allowed` is empty.
int cpu_for_llvmpipe_thread(int index, const std::vector<int>& allowed);

// True unless GLINT_NO_THREAD_PINNING is set to something other than "" or "0".
bool llvmpipe_thread_pinning_enabled();

struct LlvmpipeThreadPinning {
  int threads = 0;  // llvmpipe threads found in this process
  int pinned = 0;   // of them, pinned to one CPU each
};

// Pins every llvmpipe thread of this process that exists now (call it after the context was
// created) to cpu_for_llvmpipe_thread of its index among the CPUs that the calling thread may run
// on (its affinity mask: taskset, cgroups and Slurm's allocation are respected). Pins nothing
// where pinning is disabled, off Linux, or where the calling thread may run on one CPU only.
LlvmpipeThreadPinning pin_llvmpipe_threads();

}  // namespace glint
