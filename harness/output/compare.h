#pragma once
// Comparing two sweeps' results, cell by cell: the regression check a project's CI runs after a
// change (`relieflab compare BASE_DIR NEW_DIR [--tolerances FILE]`). Cells are matched by key,
// and where keys differ only through fields that do not change what is measured (frames, a
// config's name, image output), by identity: technique, its parameters, scene, view, viewport
// and texture resolution. Per metric a cell got worse when the new value is worse than the
// base's by more than max(abs, rel * |base|) in the metric's direction.
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rl {

struct MetricTolerance {
  bool lower_is_better = true;
  double abs = 0;  // in the metric's units
  double rel = 0;  // of the base value's magnitude
};

// The defaults: every deterministic error column (llvmpipe renders are byte-identical, so an
// identical re-run changes nothing) and fetches_mean as the hardware-independent cost. Frame
// times are not compared unless a tolerance file names them (they are noise on a shared CPU).
std::map<std::string, MetricTolerance> default_tolerances();

// Overrides and additions from a TOML file:
//   [tolerances]
//   wrong_pct = { abs = 0.5 }
//   frame_ms = { rel = 0.3 }          # added: a measured column, lower is better
//   psnr_db = { abs = 1, lower_is_better = false }
// Throws ConfigError naming the file and key on an unknown column, key or bad value.
void read_tolerances(const std::string& path, std::map<std::string, MetricTolerance>& into);

struct CellChange {
  std::string technique, metric, cell;  // cell: scene, view, viewport, texture and parameters
  double base = 0, now = 0;
  // The parts of the two rows' provenance that differ ("programs, technique_code"), "" when
  // they were measured from the same code and inputs (output/provenance.h).
  std::string measured_from;
};

struct Comparison {
  std::vector<CellChange> worse, better;
  std::vector<std::string> only_base, only_new;  // cells present on one side only
  size_t matched_by_key = 0, matched_by_identity = 0;
  // Matched cells whose rows were measured from other code or inputs, by the parts that differ:
  // what a regression check reads beside the numbers (which change came from the code).
  std::map<std::string, size_t> measured_from_differs;
  // Cells of the base run absent from the new run are tolerated (comparing a subset on
  // purpose); by default they fail the comparison.
  bool allow_missing = false;
  bool regressed() const { return !worse.empty(); }
  // Why the new run cannot pass as the base run's equal ("" when it can): no cell matched (an
  // empty run, another sweep), or base cells missing from it (one shard of several, a run cut
  // short) unless allow_missing. A CI check must not pass a broken run.
  std::string incomplete() const;
  bool failed() const { return regressed() || !incomplete().empty(); }
};

// Rows as the result store holds them (keyed); `tolerances` as above.
Comparison compare_rows(const std::map<std::string, nlohmann::ordered_json>& base,
                        const std::map<std::string, nlohmann::ordered_json>& now,
                        const std::map<std::string, MetricTolerance>& tolerances);

// Every row of a run's output folder (DIR/results.sqlite) by key. Throws ConfigError when the
// folder has no results.
std::map<std::string, nlohmann::ordered_json> read_run_rows(const std::string& dir);

// Reads DIR/results.sqlite of both runs and compares them. Throws ConfigError when a folder has
// no results.
Comparison compare_runs(const std::string& base_dir, const std::string& new_dir,
                        const std::map<std::string, MetricTolerance>& tolerances);

// The report a person reads: regressions per technique and metric, improvements, one-sided
// cells, and a last line saying whether it regressed or was incomplete.
std::string format_comparison(const Comparison& c);

}  // namespace rl
