// relieflab compare: the regression check a project's CI runs on its own sweeps. An identical
// re-run (llvmpipe renders are deterministic) reports nothing, also when the cells' keys changed
// through a field that does not change what is measured (frames); a deliberately worsened
// shader -- relief with one binary step fewer, under the same name and parameters -- is caught
// on the default sweep's relief cells and the CLI exits 1; tolerance files are checked.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "core/error.h"
#include "output/compare.h"
#include "run/runner.h"
#include "support/test_support.h"
#include "technique/shader_technique.h"

namespace rl {
namespace {

// The default sweep's relief cells on its first real map and the pyramids, at 96^2, one frame
// (the whole default sweep takes minutes): 2 scenes x 4 settings x 4 views.
SweepConfig default_relief_subset() {
  SweepConfig c = default_sweep_config();
  std::vector<SceneDesc> scenes;
  for (const SceneDesc& s : c.scenes)
    if (s.name == "panel" || s.name == "pyramids") scenes.push_back(s);
  c.scenes = scenes;
  std::vector<TechniqueSweep> techniques;
  for (TechniqueSweep t : c.techniques)
    if (t.name == "relief") {
      t.scenes = {"panel", "pyramids"};
      techniques.push_back(t);
    }
  c.techniques = techniques;
  c.viewports = {{96, 96}};
  c.frames = 1;
  c.warmup = 0;
  c.write_images = false;
  c.tables.clear();
  c.plots.clear();
  return c;
}

void run_into(const SweepConfig& c, const std::string& dir) {
  RunOptions opt;
  opt.out_dir = dir;
  opt.progress = false;
  run_sweep(c, opt);
}

// relief as its plugin describes it, but its shader compiled with one binary step fewer: the
// kind of change a shader edit makes while the technique's name and parameters stay the same.
class WorsenedRelief final : public ShaderTechnique {
 public:
  WorsenedRelief(const TechniqueInfo& info, ParamValues p)
      : ShaderTechnique(std::move(p)), info_(info) {}
  const TechniqueInfo& info() const override { return info_; }

 protected:
  std::string intersect_file() const override { return "techniques/relief/relief.glsl"; }
  Defines parameter_defines() const override {
    return {{"RL_LINEAR_STEPS", std::to_string(param<int>("linear_steps"))},
            {"RL_BINARY_STEPS", std::to_string(std::max(0, param<int>("binary_steps") - 1))}};
  }

 private:
  TechniqueInfo info_;
};

// What compare watches by default is what the columns declare (core/columns.h), pinned here:
// a declaration that stops watching a column, or loosens it, fails.
TEST(Compare, DefaultTolerancesAreTheColumnsDeclarations) {
  const auto tol = default_tolerances();
  const std::vector<std::string> watched = {"ao_err_mean",
                                            "artifact_pct",
                                            "false_pct",
                                            "fetches_mean",
                                            "frag_fetches_mean",
                                            "iterations_mean",
                                            "missed_pct",
                                            "normal_err_mean_deg",
                                            "object_disagree_pct",
                                            "object_shadow_disagree_pct",
                                            "pos_err_p99",
                                            "pos_err_rmse",
                                            "pos_err_texels_mean",
                                            "psnr_covered_db",
                                            "psnr_db",
                                            "relief_shadow_disagree_pct",
                                            "shadow_disagree_pct",
                                            "ssim",
                                            "warp_fetches_mean",
                                            "warp_fetches_per_px",
                                            "wrong_pct"};
  std::vector<std::string> names;
  for (const auto& [name, t] : tol) names.push_back(name);
  EXPECT_EQ(names, watched);
  EXPECT_TRUE(tol.at("wrong_pct").lower_is_better);
  EXPECT_EQ(tol.at("wrong_pct").abs, 0.25);
  EXPECT_EQ(tol.at("pos_err_rmse").rel, 0.02);
  EXPECT_FALSE(tol.at("psnr_db").lower_is_better);
  EXPECT_EQ(tol.at("ssim").abs, 0.002);
}

TEST(Compare, AnIdenticalRerunReportsNothing) {
  const std::string dir = test::scratch_dir("compare_same");
  SweepConfig c = default_relief_subset();
  run_into(c, dir + "/base");
  c.frames = 2;  // changes every key, not what is measured: cells match by identity
  run_into(c, dir + "/new");
  const Comparison cmp = compare_runs(dir + "/base", dir + "/new", default_tolerances());
  EXPECT_EQ(cmp.matched_by_identity, 32u);
  EXPECT_EQ(cmp.matched_by_key, 0u);
  EXPECT_TRUE(cmp.worse.empty()) << format_comparison(cmp);
  EXPECT_TRUE(cmp.better.empty()) << format_comparison(cmp);
  EXPECT_TRUE(cmp.only_base.empty() && cmp.only_new.empty());
  std::string out;
  EXPECT_EQ(test::run_cli("compare " + dir + "/base " + dir + "/new", out), 0) << out;
  EXPECT_NE(out.find("-> ok"), std::string::npos) << out;
}

TEST(Compare, AWorsenedShaderIsCaughtOnTheDefaultSweep) {
  const std::string dir = test::scratch_dir("compare_worse");
  const SweepConfig c = default_relief_subset();
  run_into(c, dir + "/base");
  auto& registry = TechniqueRegistry::instance();
  const TechniqueEntry original = *registry.find("relief");
  registry.remove("relief");
  TechniqueEntry worse = original;
  worse.create = [info = original.info](const ParamValues& p) {
    return std::make_unique<WorsenedRelief>(info, p);
  };
  registry.add(worse);
  run_into(c, dir + "/new");
  registry.remove("relief");
  registry.add(original);

  const Comparison cmp = compare_runs(dir + "/base", dir + "/new", default_tolerances());
  EXPECT_EQ(cmp.matched_by_key, 32u);
  ASSERT_TRUE(cmp.regressed());
  std::set<std::string> cells;
  for (const CellChange& ch : cmp.worse) {
    EXPECT_EQ(ch.technique, "relief");
    cells.insert(ch.cell);
  }
  // One bisection fewer doubles the refinement's last interval: most cells get worse somewhere
  // (measured: 96 metric regressions over the 32 cells).
  EXPECT_GE(cells.size(), 16u) << format_comparison(cmp);
  std::string out;
  EXPECT_EQ(test::run_cli("compare " + dir + "/base " + dir + "/new", out), 1) << out;
  EXPECT_NE(out.find("WORSE beyond tolerance"), std::string::npos);
  EXPECT_NE(out.find("relief / pos_err_rmse"), std::string::npos);
  EXPECT_NE(out.find("REGRESSED"), std::string::npos);
  // Loose enough tolerances let it pass: the tolerance file is what a project tunes.
  const std::string loose = dir + "/loose.toml";
  std::ofstream(loose) << "[tolerances]\n"
                          "wrong_pct = { abs = 100 }\nmissed_pct = { abs = 100 }\n"
                          "false_pct = { abs = 100 }\nartifact_pct = { abs = 100 }\n"
                          "pos_err_rmse = { rel = 100 }\npos_err_p99 = { rel = 100 }\n"
                          "pos_err_texels_mean = { rel = 100 }\n"
                          "normal_err_mean_deg = { abs = 100 }\npsnr_db = { abs = 100 }\n"
                          "psnr_covered_db = { abs = 100 }\n"
                          "ssim = { abs = 1 }\nfetches_mean = { rel = 100 }\n";
  EXPECT_EQ(test::run_cli("compare " + dir + "/base " + dir + "/new --tolerances " + loose, out), 0)
      << out;
}

TEST(Compare, CellsOnOneSideAndEmptyColumnsAreReported) {
  auto row = [](const std::string& scene, double el, double wrong) {
    nlohmann::ordered_json r = {
        {"technique", "normal"}, {"scene", scene},     {"elevation_deg", el}, {"azimuth_deg", 30},
        {"viewport", "64x64"},   {"texture_res", 256}, {"wrong_pct", wrong}};
    return r;
  };
  std::map<std::string, nlohmann::ordered_json> base = {
      {"a", row("s", 45, 1.0)}, {"b", row("s", 20, 2.0)}, {"c", row("t", 45, 3.0)}};
  std::map<std::string, nlohmann::ordered_json> now = {
      {"a", row("s", 45, 1.2)}, {"x", row("s", 20, 1.0)}, {"d", row("u", 45, 0.0)}};
  now["a"]["wrong_pct"] = nullptr;  // nothing measured any more: reported as worse
  const Comparison c = compare_rows(base, now, default_tolerances());
  ASSERT_EQ(c.worse.size(), 1u);
  EXPECT_EQ(c.worse[0].metric, "wrong_pct");
  ASSERT_EQ(c.better.size(), 1u);  // "b" and "x" are one cell under another key: 2.0 -> 1.0
  EXPECT_EQ(c.better[0].base, 2.0);
  EXPECT_EQ(c.matched_by_key, 1u);
  EXPECT_EQ(c.matched_by_identity, 1u);
  EXPECT_EQ(c.only_base.size(), 1u);
  EXPECT_EQ(c.only_new.size(), 1u);
}

// A CI check must not pass a broken run: an empty run or another sweep (nothing matches) and
// one shard of several or a run cut short (base cells missing) fail unless a subset is meant.
TEST(Compare, AnEmptyOrPartialNewRunFails) {
  auto row = [](const std::string& scene, double el) {
    return nlohmann::ordered_json{
        {"technique", "normal"}, {"scene", scene},     {"elevation_deg", el}, {"azimuth_deg", 30},
        {"viewport", "64x64"},   {"texture_res", 256}, {"wrong_pct", 1.0}};
  };
  const std::map<std::string, nlohmann::ordered_json> base = {
      {"a", row("s", 45)}, {"b", row("s", 20)}, {"c", row("t", 45)}};
  Comparison empty = compare_rows(base, {}, default_tolerances());
  EXPECT_FALSE(empty.regressed());
  EXPECT_TRUE(empty.failed());
  EXPECT_NE(format_comparison(empty).find("-> INCOMPLETE: no cell of the base run"),
            std::string::npos)
      << format_comparison(empty);
  Comparison other = compare_rows(base, {{"z", row("u", 45)}}, default_tolerances());
  EXPECT_TRUE(other.failed());
  Comparison shard = compare_rows(base, {{"a", row("s", 45)}}, default_tolerances());
  EXPECT_TRUE(shard.failed());
  EXPECT_NE(format_comparison(shard).find("2 cell(s) of the base run are missing"),
            std::string::npos)
      << format_comparison(shard);
  shard.allow_missing = true;
  EXPECT_FALSE(shard.failed()) << format_comparison(shard);
  EXPECT_NE(format_comparison(shard).find("-> ok"), std::string::npos);
  // Extra cells in the new run are reported and do not fail it (a sweep that grew).
  std::map<std::string, nlohmann::ordered_json> grown = base;
  grown["d"] = row("v", 45);
  EXPECT_FALSE(compare_rows(base, grown, default_tolerances()).failed());
}

TEST(Compare, ToleranceFilesAreChecked) {
  const std::string dir = test::scratch_dir("compare_tolerances");
  std::filesystem::create_directories(dir);
  auto refused = [&](const std::string& text, const std::string& expect) {
    const std::string path = dir + "/t.toml";
    std::ofstream(path) << text;
    auto tol = default_tolerances();
    try {
      read_tolerances(path, tol);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  };
  refused("[tolerances]\nwrong_percent = { abs = 1 }\n",
          "'wrong_percent' is not a measured column");
  refused("[tolerances]\nwrong_pct = 1\n", "'wrong_pct' must be a table");
  refused("[tolerances]\nwrong_pct = { absolute = 1 }\n", "absolute");
  refused("[tolerances]\nwrong_pct = { abs = -1 }\n", "abs");
  refused("[thresholds]\n", "thresholds");
  // A column's declared direction is not the file's to reverse (a regression would read better).
  refused("[tolerances]\nwrong_pct = { abs = 1, lower_is_better = false }\n",
          "'wrong_pct' is declared lower-is-better (by metrics); a tolerance file cannot reverse");
  std::ofstream(dir + "/ok.toml") << "[tolerances]\nframe_ms = { rel = 0.3 }\n";
  auto tol = default_tolerances();
  read_tolerances(dir + "/ok.toml", tol);
  ASSERT_TRUE(tol.count("frame_ms"));
  EXPECT_TRUE(tol["frame_ms"].lower_is_better);
  EXPECT_EQ(tol["frame_ms"].rel, 0.3);
  std::string out;
  EXPECT_EQ(test::run_cli("compare " + dir + " " + dir, out), 2) << out;  // no results there
  EXPECT_NE(out.find("no results.sqlite"), std::string::npos) << out;
}

}  // namespace
}  // namespace rl
