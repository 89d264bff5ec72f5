// The whole default sweep (configs/default.toml, built in) from an empty output folder, with its
// op counts and cost model (the default) and without them (cost_model = "none"): the two times'
// ratio is what the op-counting frames add to a sweep. And what the rows' provenance adds to it
// (run/cell_provenance.h): every input file read and digested once, every program the sweep drew
// composed and digested once, and the reuse plan over its stored rows, each cold, against the
// sweep's own time.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <benchmark/benchmark.h>

#include "config/config.h"
#include "core/elapsed.h"
#include "core/hash.h"
#include "gl/shader_library.h"
#include "output/result_store.h"
#include "run/cell_provenance.h"
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

// The provenance's work for one run of the default sweep, cold (no memo): its three parts in
// ms, and their share of the sweep's own time from an empty folder.
void BM_DefaultSweepProvenance(benchmark::State& state) {
  const SweepConfig config = default_sweep_config();
  const std::string out =
      (std::filesystem::temp_directory_path() / "relieflab-bench-provenance").string();
  std::filesystem::remove_all(out);
  RunOptions opt;
  opt.out_dir = out;
  opt.progress = false;
  const auto sweep_start = std::chrono::steady_clock::now();
  run_sweep(config, opt);
  const double sweep_ms = ms_since(sweep_start);
  const ResultStore store(out + "/results.sqlite", ResultStore::Access::ReadOnly);
  std::map<std::string, ProgramDesc> programs;  // every distinct program the sweep drew
  for (const std::string& key : store.keys())
    for (const ProgramDesc& d : parse_programs(store.programs(key)))
      programs.emplace(program_digest(d) + d.owner, d);
  for (auto _ : state) {
    auto t0 = std::chrono::steady_clock::now();
    for (const auto& [scene, inputs] : config.scene_inputs)
      for (const SceneInput& in : inputs) {
        std::ifstream f(in.path, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(f)), {});
        benchmark::DoNotOptimize(fnv1a64(bytes));
      }
    const double inputs_ms = ms_since(t0);
    t0 = std::chrono::steady_clock::now();
    for (const auto& [key, d] : programs) {
      std::string text = compose_glsl({d.vertex_file}, d.defines).text;
      text += compose_glsl(d.fragment_files, d.defines).text;
      if (!d.geometry_file.empty()) text += compose_glsl({d.geometry_file}, d.defines).text;
      benchmark::DoNotOptimize(fnv1a64(text));
    }
    const double programs_ms = ms_since(t0);
    t0 = std::chrono::steady_clock::now();
    const ProvenanceContext context = provenance_context(config, renderer_identity());
    std::set<std::string> keys = store.keys();
    const ReusePlan plan = plan_reuse(config, expand_cells(config), store, keys, context);
    const double plan_ms = ms_since(t0);
    state.counters["inputs_ms"] = inputs_ms;
    state.counters["programs_ms"] = programs_ms;
    state.counters["plan_ms"] = plan_ms;
    state.counters["programs"] = double(programs.size());
    state.counters["rows_reused"] = double(plan.reuse.size());
    state.counters["sweep_ms"] = sweep_ms;
    state.counters["share_pct"] = 100 * (inputs_ms + programs_ms + plan_ms) / sweep_ms;
  }
}

BENCHMARK(BM_DefaultSweepProvenance)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace rl

BENCHMARK_MAIN();
