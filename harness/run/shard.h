#pragma once
// Sweeps split over machines: `relieflab run CONFIG --shard I/N` measures a deterministic slice
// of the cells, and `relieflab merge OUT_DIR SHARD_DIRS...` merges the shards' stores and writes
// the tables as one run would (a Slurm job array runs the shards: scripts/slurm/).
//
// Cells that share a truth trace (scene, texture resolution, viewport, view) stay in one shard,
// so no truth is traced twice; the groups are dealt out by estimated cost, largest first, each
// to the shard with the least so far (ties by index), so every shard gets the same groups on
// every machine.
#include <string>
#include <vector>

#include "config/config.h"
#include "run/cells.h"

namespace rl {

struct ShardSpec {
  int index = 0, count = 1;  // shard `index` of `count`, 0-based
  bool active() const { return count > 1; }
  std::string text() const { return std::to_string(index) + "/" + std::to_string(count); }
};

// "I/N" with 0 <= I < N <= 10000; throws ConfigError otherwise.
ShardSpec parse_shard(const std::string& text);

// The estimated cost of a cell group sharing one truth: the truth's rays (primary, and the
// hemisphere rays of ambient occlusion) and each cell's frames, in pixels.
double truth_group_cost(const SweepConfig& config, const std::vector<const Cell*>& group);

// The cells of one shard, in the config's order.
std::vector<Cell> shard_cells(const SweepConfig& config, const std::vector<Cell>& cells,
                              const ShardSpec& shard);

// What a run writes next to its store (OUT/sweep.json): the config's text, folder and hash,
// and the shard it ran; merge checks that every shard ran the same config.
void write_sweep_record(const SweepConfig& config, const ShardSpec& shard,
                        const std::string& out_dir);
// A run writes rows.csv and the tables of its own cells: into a folder that recorded another
// shard (a whole run, or another slice), it would silently replace them with a part. Throws
// ConfigError naming both before anything is written.
void refuse_another_shard(const ShardSpec& shard, const std::string& out_dir);

struct MergeSummary {
  size_t shards = 0, rows_added = 0, cells = 0, missing = 0;
};

// Merges the stores of `shard_dirs` into out_dir's (rows already there are kept: merging twice
// changes nothing) and writes rows.csv, the tables and the Pareto fronts for the whole sweep.
// Throws ConfigError naming the folder when one has no run, or ran another config.
MergeSummary merge_shards(const std::string& out_dir, const std::vector<std::string>& shard_dirs);

// How far a run has got, from its store(s): one output folder (a whole run or one shard:
// its own slice is the total), or several shards' folders of one sweep (the whole sweep is).
// Cells done of all, truth traces whose cells are all done, and per technique. Throws
// ConfigError like merge_shards.
struct RunStatus {
  std::string name, source, shard;  // shard: "i/n", or "" for a whole run or several folders
  size_t cells = 0, done = 0, truths = 0, truths_done = 0;
  size_t unusable = 0;  // stored rows that cannot stand for their cell (not counted as done)
  // Stored rows measured from other code or inputs than this build's and the files' now: not
  // counted as done (a run measures them again), and why, as a run would say it.
  size_t stale = 0;
  std::vector<std::pair<std::string, size_t>> stale_reasons;
  bool files_changed = false;  // the config's files read differently now than when it ran
  std::vector<std::pair<std::string, std::pair<size_t, size_t>>> techniques;  // done, all
};
RunStatus run_status(const std::vector<std::string>& dirs);
// Rewrites a run folder's rows.csv, tables, Pareto fronts and report from its store and its
// recorded config (`relieflab report DIR`); returns how many of its cells have rows.
size_t rewrite_outputs(const std::string& dir);
std::string format_run_status(const RunStatus& s);

}  // namespace rl
