#pragma once
// Runs a sweep: for each relief asset (scene, texture resolution) it builds the map, its GPU
// textures and its Embree truth once; for each (viewport, view) it traces the truth once and
// measures every technique and parameter setting against it. Rows go to the result store as
// they finish; tables and rows.csv are rewritten from the store at the end.
#include <ostream>
#include <string>

#include "config/config.h"
#include "output/result_store.h"
#include "run/cells.h"
#include "run/shard.h"

namespace rl {

struct RunOptions {
  std::string out_dir = "out/default";
  bool progress = true;  // one progress line per cell on stderr
  ShardSpec shard;       // only this slice of the cells (run/shard.h)
};

struct SweepSummary {
  size_t cells = 0;
  size_t already_done = 0;  // found in the store, measured from what this run has, not redone
  size_t remeasured = 0;    // found in the store, measured from other code or inputs: redone
  size_t new_rows = 0;
  size_t truth_traces = 0;  // truth G-buffers traced in this run
  size_t asset_builds = 0;
  double elapsed_s = 0;
  std::string renderer;
};

SweepSummary run_sweep(const SweepConfig& config, const RunOptions& options);

// rows.csv, the tables and the Pareto fronts of `cells` from the rows `store` has of them. A
// stored row that cannot stand for its cell (cut short, text where a measure belongs, another
// cell's identity: the checks a run makes before reusing one) is left out with a warning on
// stderr, never published; returns how many were left out.
size_t write_sweep_outputs(const SweepConfig& config, const std::vector<Cell>& cells,
                           const ResultStore& store, const std::string& out_dir);

// Why the row `store` holds for `cell` cannot stand for it ("" when it can): the check a run
// makes before reusing a row and before publishing one.
std::string stored_row_problem(const ResultStore& store, const Cell& cell);

}  // namespace rl
