// Safety-radius precompute (relief_robust) at 128^2 and 256^2, all cores, no disk cache.
// The paper reports about 10 s for 128^2 on its 2006 GPU (Baboud & Decoret, Section 3.5).
#include <benchmark/benchmark.h>

#include "../techniques/relief_robust/safety_radius.h"
#include "relief/procedural.h"

namespace rl {
namespace {

void BM_SafetyRadius(benchmark::State& state, std::string kind) {
  ReliefMap map = make_procedural(kind, int(state.range(0)), {}, 10.0, "bench");
  quantize_8bit(map);
  SafetyRadii r;
  for (auto _ : state) {
    r = compute_safety_radii(map, SafetyRadiusOptions{});
    benchmark::DoNotOptimize(r.radius.data());
  }
  double mean = 0;
  for (uint8_t v : r.radius) mean += v;
  state.counters["mean_radius"] = mean / r.radius.size();
  state.counters["zero_pct"] = 100.0 * r.zero_count() / r.radius.size();
}

BENCHMARK_CAPTURE(BM_SafetyRadius, pyramids, "pyramids")
    ->Arg(128)
    ->Arg(256)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SafetyRadius, bricks, "bricks")
    ->Arg(128)
    ->Arg(256)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SafetyRadius, sines, "sines")
    ->Arg(128)
    ->Arg(256)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace rl

BENCHMARK_MAIN();
