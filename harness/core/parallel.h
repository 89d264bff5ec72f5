#pragma once
// A minimal parallel loop over [0, n) in contiguous chunks on the cores this process may use.
// Used for per-pixel truth tracing and precomputation, where each index writes its own output.
#include <algorithm>
#include <atomic>
#include <functional>
#include <string>
#include <thread>
#include <vector>

namespace rl {

// The threads parallel_for runs on: the cores this process may use, not every core of the
// machine (std::thread::hardware_concurrency counts those, so a sweep bound to 2 of a node's 64
// cores by taskset, Slurm or a container ran 64 threads on them). The least of the affinity
// mask's cores (taskset, numactl, Slurm's task binding, a cpuset) and a cgroup v2 CPU quota
// (`docker --cpus`), rounded up; at least 1. Fixed at the first call, so scratch sized per
// worker by it covers every worker for the rest of the process.
size_t parallel_workers();

// How many cores a cgroup v2 `cpu.max` line ("<quota> <period>", or "max <period>" for none)
// grants, rounded up; 0 for no quota or a line that is not one.
size_t cores_of_cpu_max(const std::string& line);

// `body(worker, begin, end)`: `worker` in [0, parallel_workers()) names the thread running the
// chunk, so a loop can keep one scratch or accumulator per thread and combine them after.
inline void parallel_for_workers(
    size_t n, const std::function<void(size_t worker, size_t begin, size_t end)>& body,
    size_t grain = 64) {
  const size_t threads = parallel_workers();
  if (n <= grain || threads == 1) {
    body(0, 0, n);
    return;
  }
  std::atomic<size_t> next{0};
  auto worker = [&](size_t id) {
    for (;;) {
      size_t begin = next.fetch_add(grain);
      if (begin >= n) return;
      body(id, begin, std::min(n, begin + grain));
    }
  };
  std::vector<std::thread> pool;
  for (size_t i = 1; i < threads; ++i) pool.emplace_back(worker, i);
  worker(0);
  for (auto& t : pool) t.join();
}

inline void parallel_for(size_t n, const std::function<void(size_t begin, size_t end)>& body,
                         size_t grain = 64) {
  parallel_for_workers(
      n, [&](size_t, size_t begin, size_t end) { body(begin, end); }, grain);
}

}  // namespace rl
