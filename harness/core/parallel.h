#pragma once
// A minimal parallel loop over [0, n) in contiguous chunks on the machine's cores. Used for
// per-pixel truth tracing and precomputation, where each index writes its own output.
#include <algorithm>
#include <atomic>
#include <functional>
#include <thread>
#include <vector>

namespace rl {

inline void parallel_for(size_t n, const std::function<void(size_t begin, size_t end)>& body,
                         size_t grain = 64) {
  const size_t threads = std::max(1u, std::thread::hardware_concurrency());
  if (n <= grain || threads == 1) {
    body(0, n);
    return;
  }
  std::atomic<size_t> next{0};
  auto worker = [&] {
    for (;;) {
      size_t begin = next.fetch_add(grain);
      if (begin >= n) return;
      body(begin, std::min(n, begin + grain));
    }
  };
  std::vector<std::thread> pool;
  for (size_t i = 1; i < threads; ++i) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
}

}  // namespace rl
