// The whole default sweep (configs/default.toml, built in) from an empty output folder, with its
// op counts and cost model (the default) and without them (cost_model = "none"): the two times'
// ratio is what the op-counting frames add to a sweep.
#include <filesystem>

#include <benchmark/benchmark.h>

#include "config/config.h"
#include "run/runner.h"

namespace rl {
namespace {

void BM_DefaultSweep(benchmark::State& state) {
  SweepConfig config = default_sweep_config();
  if (state.range(0) == 0) {
    config.cost_model.reset();
    config.cost_model_name = "none";
  }
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

BENCHMARK(BM_DefaultSweep)
    ->ArgName("cost_model")
    ->Arg(1)
    ->Arg(0)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace
}  // namespace rl

BENCHMARK_MAIN();
