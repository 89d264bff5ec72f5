// The whole default sweep (configs/default.toml, built in) from an empty output folder.
#include <filesystem>

#include <benchmark/benchmark.h>

#include "config/config.h"
#include "run/runner.h"

namespace rl {
namespace {

void BM_DefaultSweep(benchmark::State& state) {
  const SweepConfig config = default_sweep_config();
  const std::string out =
      (std::filesystem::temp_directory_path() / "relieflab-bench-sweep").string();
  for (auto _ : state) {
    std::filesystem::remove_all(out);
    RunOptions opt;
    opt.out_dir = out;
    opt.progress = false;
    SweepSummary s = run_sweep(config, opt);
    state.counters["cells"] = double(s.cells);
    state.counters["truth_traces"] = double(s.truth_traces);
  }
}

BENCHMARK(BM_DefaultSweep)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
}  // namespace rl

BENCHMARK_MAIN();
