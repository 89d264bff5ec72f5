// Sweeps end to end: truth traced once per view and shared, no work on a re-run, a killed
// sweep resumes without losing or duplicating rows, outputs have the promised columns.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "config/config.h"
#include "output/result_store.h"
#include "run/cells.h"
#include "run/runner.h"
#include "support/test_support.h"

namespace rl {
namespace {

namespace fs = std::filesystem;

// 3 techniques x 4 views; relief and parallax with 4 parameter settings each (normal mapping
// has no parameters, so it runs once per view): 36 cells that share 4 truths.
const char* kThreeByFourByFour = R"(
[sweep]
name = "three_by_four"
elevations = [90, 45, 20, 5]
azimuths = [30]
viewports = [24]
frames = 1
warmup = 0
[[scene]]
name = "bricks"
relief = { procedural = "bricks", resolution = 32 }
[[technique]]
name = "relief"
linear_steps = [4, 8, 16, 32]
[[technique]]
name = "parallax"
offset_limiting = [false, true]
bias = [0.0, 0.1]
[[technique]]
name = "normal"
)";

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

TEST(Sweep, TruthOncePerViewAndNoWorkOnARerun) {
  const std::string out = test::scratch_dir("out");
  SweepConfig config = parse_sweep_config(kThreeByFourByFour, "three_by_four.toml", ".");
  RunOptions opt;
  opt.out_dir = out;
  opt.progress = false;
  SweepSummary first = run_sweep(config, opt);
  EXPECT_EQ(first.cells, (4u + 4u + 1u) * 4u);
  EXPECT_EQ(first.new_rows, first.cells);
  EXPECT_EQ(first.truth_traces, 4u);
  EXPECT_EQ(first.asset_builds, 1u);
  EXPECT_NE(read(out + "/run.log").find("traced truth 4 times"), std::string::npos);

  SweepSummary second = run_sweep(config, opt);
  EXPECT_EQ(second.new_rows, 0u);
  EXPECT_EQ(second.already_done, first.cells);
  EXPECT_EQ(second.truth_traces, 0u);
  EXPECT_EQ(second.asset_builds, 0u);

  // rows.csv: one row per cell, with the promised columns.
  const std::vector<std::string> csv = lines(read(out + "/rows.csv"));
  ASSERT_EQ(csv.size(), first.cells + 1);
  for (const char* col : {"technique",
                          "scene",
                          "elevation_deg",
                          "azimuth_deg",
                          "texture_res",
                          "viewport",
                          "linear_steps",
                          "binary_steps",
                          "offset_limiting",
                          "bias",
                          "missed_pct",
                          "false_pct",
                          "pos_err_mean",
                          "pos_err_rmse",
                          "pos_err_p99",
                          "pos_err_max",
                          "pos_err_texels_rmse",
                          "artifact_pct",
                          "normal_err_mean_deg",
                          "normal_err_p99_deg",
                          "psnr_db",
                          "ssim",
                          "shadow_disagree_pct",
                          "fetches_mean",
                          "fetches_p99",
                          "fetches_max",
                          "frame_ms",
                          "precompute_ms",
                          "memory_bytes",
                          "image_render",
                          "image_truth",
                          "image_error"})
    EXPECT_NE(csv[0].find(col), std::string::npos) << col;
  // Images of every row exist.
  SweepConfig again = parse_sweep_config(kThreeByFourByFour, "three_by_four.toml", ".");
  ResultStore store(out + "/results.sqlite");
  for (const Cell& c : expand_cells(again)) {
    auto row = store.row(c.key);
    ASSERT_TRUE(row);
    for (const char* img : {"image_render", "image_truth", "image_error"})
      EXPECT_TRUE(fs::exists(out + "/" + (*row)[img].get<std::string>())) << img;
  }
  // The default table exists and has one line per (scene, elevation, technique, settings).
  EXPECT_NE(read(out + "/table.md").find("| scene | elevation_deg | technique |"),
            std::string::npos);
}

TEST(Sweep, KilledMidwayResumesWithoutLosingOrDuplicatingRows) {
  const std::string dir = test::scratch_dir("kill");
  fs::create_directories(dir);
  const std::string config_path = dir + "/slow.toml";
  std::ofstream(config_path) << R"(
[sweep]
name = "slow"
elevations = [80, 60, 45, 30, 20, 10]
viewports = [96]
frames = 40
[[scene]]
name = "pyramids"
relief = { procedural = "pyramids", resolution = 64 }
[[technique]]
name = "relief"
linear_steps = [16, 32, 64, 128]
)";
  const std::string out = dir + "/out";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    execl(RELIEFLAB_CLI, RELIEFLAB_CLI, "run", config_path.c_str(), "--out", out.c_str(), "-q",
          (char*)nullptr);
    _exit(127);
  }
  // Kill it hard once a few rows are committed.
  size_t before = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline) {
    if (fs::exists(out + "/results.sqlite")) {
      try {
        before = ResultStore(out + "/results.sqlite").keys().size();
      } catch (const std::exception&) {
        before = 0;  // the sweep is still creating the store: look again
      }
      if (before >= 3) break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the sweep finished before it could be killed";
  before = ResultStore(out + "/results.sqlite").keys().size();
  EXPECT_FALSE(fs::exists(out + "/rows.csv"));  // outputs come at the end

  SweepConfig config = load_sweep_config(config_path);
  RunOptions opt;
  opt.out_dir = out;
  opt.progress = false;
  SweepSummary resumed = run_sweep(config, opt);
  EXPECT_EQ(resumed.cells, 24u);
  EXPECT_EQ(resumed.already_done, before);
  EXPECT_EQ(resumed.new_rows, 24u - before);
  EXPECT_EQ(ResultStore(out + "/results.sqlite").keys().size(), 24u);
  const std::vector<std::string> csv = lines(read(out + "/rows.csv"));
  ASSERT_EQ(csv.size(), 25u);
  std::set<std::string> unique(csv.begin() + 1, csv.end());
  EXPECT_EQ(unique.size(), 24u);
}

TEST(ResultStore, ShardsMergeByKey) {
  const std::string dir = test::scratch_dir("shards");
  fs::create_directories(dir);
  {
    ResultStore a(dir + "/a.sqlite"), b(dir + "/b.sqlite");
    a.insert("k1", {{"v", 1}});
    a.insert("k2", {{"v", 2}});
    b.insert("k2", {{"v", 99}});  // same cell measured on another shard: first result wins
    b.insert("k3", {{"v", 3}});
    a.insert("k1", {{"v", 7}});  // re-inserting never duplicates or overwrites
  }
  ResultStore a(dir + "/a.sqlite");
  EXPECT_EQ(a.merge_from(dir + "/b.sqlite"), 1u);
  EXPECT_EQ(a.keys(), (std::set<std::string>{"k1", "k2", "k3"}));
  EXPECT_EQ((*a.row("k1"))["v"], 1);
  EXPECT_EQ((*a.row("k2"))["v"], 2);
}

// A repeated elevation or [[technique]] block renders each cell once.
TEST(Sweep, RepeatedViewsAndTechniquesExpandToOneCellEach) {
  const std::string text = R"(
[sweep]
name = "dup"
elevations = [45, 45, 20]
viewports = [16]
[[scene]]
name = "flat"
relief = { procedural = "flat", resolution = 8 }
[[technique]]
name = "relief"
linear_steps = [4, 4]
[[technique]]
name = "relief"
linear_steps = [4]
)";
  size_t duplicates = 0;
  const std::vector<Cell> cells =
      expand_cells(parse_sweep_config(text, "dup.toml", "."), &duplicates);
  EXPECT_EQ(cells.size(), 2u);  // 45 and 20 degrees, linear_steps = 4
  EXPECT_EQ(duplicates, 3u * 3u - 2u);
  std::set<std::string> keys;
  for (const Cell& c : cells) EXPECT_TRUE(keys.insert(c.key).second);
}

// Azimuths a full turn apart are one view (hostile input, round four: 0, 360 and -360 were three
// cells of it); within [0, 360) an azimuth keeps its value, so earlier cells keep their keys.
TEST(Sweep, AzimuthsAFullTurnApartAreOneView) {
  const std::string text = R"(
[sweep]
name = "turns"
elevations = [45]
azimuths = [0, 360, -360, 30, -330]
viewports = [16]
[[scene]]
name = "flat"
relief = { procedural = "flat", resolution = 8 }
[[technique]]
name = "relief"
)";
  size_t duplicates = 0;
  const std::vector<Cell> cells =
      expand_cells(parse_sweep_config(text, "turns.toml", "."), &duplicates);
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_EQ(duplicates, 3u);
  std::set<double> azimuths;
  for (const Cell& c : cells) azimuths.insert(c.view.azimuth_deg);
  EXPECT_EQ(azimuths, (std::set<double>{0.0, 30.0}));
}

TEST(Sweep, DefaultConfigParsesAndExpands) {
  SweepConfig c = default_sweep_config();
  EXPECT_EQ(c.name, "default");
  const std::vector<Cell> cells = expand_cells(c);
  // 4 scenes x (normal + parallax + 4 relief + relief_hierarchical_exact) x 4 elevations, + the
  // shadowed, the AO and the
  // meta-relief scene x 4 relief x 4, + the sphere x 4 relief x 4 and the silhouette sphere x 4
  // relief_silhouette x 4, + the weave x (4 relief + 4 multilayer + 4 double_depth) x 4, + the
  // cell-complex bunny x 4 cell_complex x 4, + the six-face bunny x 3 multi_heightfield x 4, +
  // (rockwall, bricks) x 3 depth_slicing x 4 and (bricks, pyramids) x odd x 4.
  EXPECT_EQ(cells.size(),
            4u * 7u * 4u + 5u * 4u * 4u + 12u * 4u + 4u * 4u + 3u * 4u + 6u * 4u + 2u * 4u);
  std::set<std::string> truths, keys;
  for (const Cell& cell : cells) {
    truths.insert(cell.truth_key);
    keys.insert(cell.key);
  }
  EXPECT_EQ(truths.size(), 12u * 4u);
  EXPECT_EQ(keys.size(), cells.size());
}

}  // namespace
}  // namespace rl

namespace rl {
namespace {

TEST(Framing, FillCoversTheViewportAtGrazingViewsWithinAFewDegrees) {
  // The default framing of a planar scene: at 5 degrees the relief fills the viewport (the old
  // whole-quad fit covered 4.3% of a 256^2 viewport), and the covered pixels' view elevations
  // stay within elevation / 4 of the nominal one.
  SweepConfig c = default_sweep_config();
  const SceneDesc& panel = c.scenes.front();
  ASSERT_EQ(panel.framing, Framing::Fill);
  SceneDesc fit = panel;
  fit.framing = Framing::Fit;
  fit.size = fit.fill_footprint;
  fit.tile = 1;
  for (double el : {5.0, 20.0}) {
    SCOPED_TRACE(el);
    const Camera cam = make_camera(panel, View{el, 30}, 64, 64);
    int hits = 0;
    double lo = 90, hi = -90;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        glm::dvec3 o, d;
        cam.pixel_ray(x, y, o, d);
        const double t = -o.z / d.z;  // the quad's plane
        const glm::dvec3 p = o + t * d;
        if (d.z < 0 && std::abs(p.x) <= 0.5 * panel.size && std::abs(p.y) <= 0.5 * panel.size) {
          ++hits;
          lo = std::min(lo, glm::degrees(std::asin(-d.z)));
          hi = std::max(hi, glm::degrees(std::asin(-d.z)));
        }
      }
    EXPECT_EQ(hits, 64 * 64);
    EXPECT_GE(lo, el - el / 4 - 1e-9);
    EXPECT_LE(hi, el + el / 4 + 1e-9);
  }
  // The fill quad keeps the texel size: more tiles, not larger ones.
  EXPECT_DOUBLE_EQ(panel.size / panel.tile, fit.size / fit.tile);
  // Measured end to end: a 5-degree cell's truth covers the whole viewport.
  SceneDesc scene = test::procedural_scene("bricks", 32, 0.08, true);
  apply_fill_framing(scene, 5, 1);
  const test::Measured m = test::measure(scene, "relief", {}, View{5, 30}, 48);
  EXPECT_EQ(m.metrics.at("covered_px"), 48 * 48);
}

}  // namespace
}  // namespace rl
