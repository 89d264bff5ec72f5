// Sweeps split into shards (run/shard.h): the shards partition the cells, keep every truth
// trace's cells together and are dealt out by cost deterministically; merging their stores gives
// the rows of a single-process run exactly (renders on llvmpipe are deterministic), merging twice
// changes nothing, and a shard of another config is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "core/error.h"
#include "output/compare.h"
#include "output/result_store.h"
#include "run/runner.h"
#include "run/shard.h"
#include "support/test_support.h"

namespace rl {
namespace {

// tests/shard_sweep.toml (also the Slurm test's): the default sweep's procedural scenes at 64^2,
// as config text (merge rebuilds the config from the text the shards recorded); truth groups of
// different costs.
std::string small_default_text(const std::string& elevations = "[90, 45, 20, 5]") {
  std::ifstream in(std::string(RELIEFLAB_TEST_DIR) + "/shard_sweep.toml");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const std::string views = "elevations = [90, 45, 20, 5]";
  text.replace(text.find(views), views.size(), "elevations = " + elevations);
  return text;
}

SweepConfig small_default(const std::string& dir = "") {
  return parse_sweep_config(small_default_text(), "shard_test.toml", dir.empty() ? "." : dir);
}

TEST(Shard, ShardsPartitionTheCellsAndKeepTruthsTogether) {
  const SweepConfig c = small_default();
  const std::vector<Cell> cells = expand_cells(c);
  for (int n : {1, 2, 3, 7}) {
    SCOPED_TRACE(n);
    std::map<std::string, int> shard_of_cell, shard_of_truth;
    std::vector<double> load(size_t(n), 0);
    for (int i = 0; i < n; ++i) {
      const std::vector<Cell> mine = shard_cells(c, cells, {i, n});
      EXPECT_EQ(mine.size(), shard_cells(c, cells, {i, n}).size());  // deterministic
      std::map<std::string, std::vector<const Cell*>> groups;
      for (const Cell& cell : mine) {
        EXPECT_TRUE(shard_of_cell.emplace(cell.key, i).second);  // in one shard only
        auto [it, fresh] = shard_of_truth.emplace(cell.truth_key, i);
        EXPECT_EQ(it->second, i);  // a truth's cells in one shard
        groups[cell.truth_key].push_back(&cell);
      }
      for (const auto& [k, g] : groups) load[size_t(i)] += truth_group_cost(c, g);
    }
    EXPECT_EQ(shard_of_cell.size(), cells.size());  // and every cell in one
    // Greedy by cost: no shard exceeds another by more than the largest group.
    std::map<std::string, std::vector<const Cell*>> all;
    for (const Cell& cell : cells) all[cell.truth_key].push_back(&cell);
    double largest = 0;
    for (const auto& [k, g] : all) largest = std::max(largest, truth_group_cost(c, g));
    EXPECT_LE(
        *std::max_element(load.begin(), load.end()) - *std::min_element(load.begin(), load.end()),
        largest + 1e-9);
  }
  EXPECT_THROW(parse_shard("3/3"), ConfigError);
  EXPECT_THROW(parse_shard("1"), ConfigError);
  EXPECT_THROW(parse_shard("a/2"), ConfigError);
  EXPECT_THROW(parse_shard("1/2x"), ConfigError);
  EXPECT_EQ(parse_shard("2/8").index, 2);
}

TEST(Shard, MergedShardsEqualASingleProcessRun) {
  const std::string dir = test::scratch_dir("shards");
  const SweepConfig c = small_default();
  RunOptions single;
  single.out_dir = dir + "/single";
  single.progress = false;
  run_sweep(c, single);
  std::vector<std::string> shard_dirs;
  for (int i = 0; i < 3; ++i) {
    RunOptions o;
    o.out_dir = dir + "/shard" + std::to_string(i);
    o.progress = false;
    o.shard = {i, 3};
    run_sweep(c, o);
    shard_dirs.push_back(o.out_dir);
  }
  // Status: one shard's folder counts its own slice; two of three shards, the whole sweep.
  const RunStatus one = run_status({shard_dirs[1]});
  EXPECT_EQ(one.shard, "1/3");
  EXPECT_EQ(one.done, one.cells);
  EXPECT_EQ(one.truths_done, one.truths);
  const RunStatus two = run_status({shard_dirs[0], shard_dirs[1]});
  EXPECT_EQ(two.cells, expand_cells(c).size());
  EXPECT_EQ(two.done, two.cells - shard_cells(c, expand_cells(c), {2, 3}).size());
  EXPECT_LT(two.truths_done, two.truths);
  EXPECT_NE(format_run_status(two).find("relief"), std::string::npos);
  const MergeSummary m = merge_shards(dir + "/merged", shard_dirs);
  EXPECT_EQ(m.shards, 3u);
  EXPECT_EQ(m.missing, 0u);
  EXPECT_EQ(m.rows_added, m.cells);
  // Every error column identical: compare with zero tolerance on every default metric.
  auto exact = default_tolerances();
  for (auto& [k, t] : exact) t.abs = t.rel = 0;
  const Comparison cmp =
      compare_rows(read_run_rows(dir + "/single"), read_run_rows(dir + "/merged"), exact);
  EXPECT_EQ(cmp.matched_by_key, m.cells);
  EXPECT_TRUE(cmp.worse.empty() && cmp.better.empty()) << format_comparison(cmp);
  EXPECT_TRUE(cmp.only_base.empty() && cmp.only_new.empty());
  EXPECT_TRUE(std::filesystem::exists(dir + "/merged/rows.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/merged/table.md"));
  // Idempotent.
  EXPECT_EQ(merge_shards(dir + "/merged", shard_dirs).rows_added, 0u);
  // A shard of another config is refused, naming it.
  RunOptions o;
  o.out_dir = dir + "/foreign";
  o.progress = false;
  run_sweep(parse_sweep_config(small_default_text("[90, 45]"), "other.toml", "."), o);
  try {
    merge_shards(dir + "/merged2", {shard_dirs[0], dir + "/foreign"});
    ADD_FAILURE() << "merged a shard of another config";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(dir + "/foreign: ran another config"), std::string::npos)
        << e.what();
  }
  std::string out;
  EXPECT_EQ(test::run_cli("merge " + dir + "/merged3 " + shard_dirs[0] + " " + shard_dirs[1] + " " +
                              shard_dirs[2],
                          out),
            0)
      << out;
  EXPECT_EQ(test::run_cli("merge " + dir + "/merged4 " + shard_dirs[0], out), 3) << out;
  EXPECT_NE(out.find("run the missing shards"), std::string::npos) << out;
}

// Hostile input, second round: the config hash covered scenes, frames and tolerance only, so shards
// of a sweep with other parameters merged; a merge into another sweep's folder mixed their rows;
// and a corrupt stored row was published in rows.csv and the tables.
TEST(Shard, MergeRefusesOtherSweepsAndPublishesNoCorruptRow) {
  const std::string dir = test::scratch_dir("shards-hostile");
  const std::string views = "[45, 5]";
  const SweepConfig c = parse_sweep_config(small_default_text(views), "shard_test.toml", ".");
  std::vector<std::string> shard_dirs;
  for (int i = 0; i < 2; ++i) {
    RunOptions o;
    o.out_dir = dir + "/shard" + std::to_string(i);
    o.progress = false;
    o.shard = {i, 2};
    run_sweep(c, o);
    shard_dirs.push_back(o.out_dir);
  }
  // The same scenes and views, other relief settings: another sweep.
  std::string text = small_default_text(views);
  const std::string steps = "linear_steps = [8, 16, 32, 64]";
  text.replace(text.find(steps), steps.size(), "linear_steps = [8, 16]");
  RunOptions o;
  o.out_dir = dir + "/other";
  o.progress = false;
  o.shard = {1, 2};
  run_sweep(parse_sweep_config(text, "shard_test.toml", "."), o);
  auto refused = [&](const std::string& out, const std::vector<std::string>& shards,
                     const std::string& expect) {
    try {
      merge_shards(out, shards);
      ADD_FAILURE() << "merged into " << out;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
    }
  };
  refused(dir + "/merged", {shard_dirs[0], dir + "/other"}, dir + "/other: ran another config");
  refused(dir + "/other", shard_dirs, dir + "/other holds another sweep");
  EXPECT_FALSE(std::filesystem::exists(dir + "/merged"));
  // A row whose measure is text: left out of the merged outputs and counted as missing.
  {
    ResultStore store(shard_dirs[0] + "/results.sqlite");
    const std::string key = *store.keys().begin();
    nlohmann::ordered_json row = *store.row(key);
    row["wrong_pct"] = "banana";
    store.erase(key);
    store.insert(key, row);
  }
  const MergeSummary m = merge_shards(dir + "/merged", shard_dirs);
  EXPECT_EQ(m.missing, 1u);
  std::ifstream csv(dir + "/merged/rows.csv");
  const std::string rows((std::istreambuf_iterator<char>(csv)), {});
  EXPECT_EQ(rows.find("banana"), std::string::npos);
  EXPECT_EQ(size_t(std::count(rows.begin(), rows.end(), '\n')), m.cells);  // header + cells - 1
}

}  // namespace
}  // namespace rl
