// parallel_for's workers: as many as the cores this process may use, each index run once.
#include <sched.h>

#include <atomic>
#include <mutex>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "core/parallel.h"

namespace rl {
namespace {

TEST(Parallel, CpuMaxLinesGiveTheirCoresRoundedUp) {
  EXPECT_EQ(cores_of_cpu_max("200000 100000"), 2u);
  EXPECT_EQ(cores_of_cpu_max("150000 100000\n"), 2u);  // 1.5 cores: both may run
  EXPECT_EQ(cores_of_cpu_max("50000 100000"), 1u);
  EXPECT_EQ(cores_of_cpu_max("max 100000"), 0u);  // no quota
  for (const char* broken :
       {"", "100000", "abc 100000", "100000 0", "-5 100000", "1e5x 100000", "1e300 1"})
    EXPECT_EQ(cores_of_cpu_max(broken), 0u) << "'" << broken << "'";
}

// Also run by CTest under `taskset -c 0` (tests/CMakeLists.txt), where hardware_concurrency
// still counts every core of the machine and a worker per core would share the one allowed.
TEST(Parallel, WorkersAreNoMoreThanTheCoresThisProcessMayUse) {
  cpu_set_t set;
  CPU_ZERO(&set);
  ASSERT_EQ(sched_getaffinity(0, sizeof set, &set), 0);
  const size_t workers = parallel_workers();
  EXPECT_GE(workers, 1u);
  EXPECT_LE(workers, size_t(CPU_COUNT(&set)));

  // Every index once, on workers numbered below parallel_workers(), each a thread of its own.
  constexpr size_t kIndices = 10000;
  std::vector<std::atomic<int>> runs(kIndices);
  std::mutex lock;
  std::set<size_t> named;
  parallel_for_workers(
      kIndices,
      [&](size_t worker, size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) ++runs[i];
        std::lock_guard<std::mutex> hold(lock);
        named.insert(worker);
      },
      7);
  for (size_t i = 0; i < kIndices; ++i) ASSERT_EQ(runs[i].load(), 1) << "index " << i;
  EXPECT_LE(named.size(), workers);
  EXPECT_LT(*named.rbegin(), workers);
}

}  // namespace
}  // namespace rl
