// Golden figures: error metrics of fixed cells, pinned in tests/golden/golden.json. A change
// that makes a technique worse (more error, or more fetches for the same error) fails here.
// Improvements pass and print a note; after checking them, regenerate the file with
//   RELIEFLAB_UPDATE_GOLDEN=1 ctest --test-dir build -R Golden
// llvmpipe renders deterministically, so values only move when the code does.
#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/test_support.h"

namespace rl {
namespace {

struct GoldenCell {
  std::string label, kind, technique;
  ParamValues params;
  View view;
  std::string base = "plane";
  EffectSet effects = {};
};

std::vector<GoldenCell> golden_cells() {
  std::vector<GoldenCell> cells;
  for (const char* kind : {"bricks", "pyramids", "sines"})
    for (double el : {45.0, 20.0}) {
      for (double steps : {8.0, 32.0})
        cells.push_back({std::string(kind) + "/relief/ls" + std::to_string(int(steps)) + "/el" +
                             std::to_string(int(el)),
                         kind,
                         "relief",
                         {{"linear_steps", steps}, {"binary_steps", 5}},
                         View{el, 30}});
      cells.push_back({std::string(kind) + "/parallax/el" + std::to_string(int(el)),
                       kind,
                       "parallax",
                       {},
                       View{el, 30}});
      for (const char* exact :
           {"relief_exact", "relief_exact_bilinear", "relief_robust", "relief_hierarchical_exact",
            "relief_window_exact", "max_mipmap", "cone_relaxed", "pom"})
        cells.push_back({std::string(kind) + "/" + exact + "/el" + std::to_string(int(el)),
                         kind,
                         exact,
                         {},
                         View{el, 30}});
    }
  // Curved bases (chapter 5): planar search vs bent rays, where the silhouette matters.
  for (const char* base : {"sphere", "torus"}) {
    const std::string b(base);
    cells.push_back({b + "/sines/relief/el20",
                     "sines",
                     "relief",
                     {{"linear_steps", 16}, {"binary_steps", 6}},
                     View{20, 30},
                     b});
    for (double exact : {0.0, 1.0})
      cells.push_back({b + "/sines/relief_silhouette/exact" + std::to_string(int(exact)) + "/el20",
                       "sines",
                       "relief_silhouette",
                       {{"linear_steps", 16}, {"binary_steps", 6}, {"exact_distance", exact}},
                       View{20, 30},
                       b,
                       {Effect::Silhouette}});
  }
  return cells;
}

// Metrics pinned: whether larger is worse, and the absolute difference that is float noise
// rather than a change in the technique (depth units, %, degrees, dB, fetches). A one-step
// change of relief's binary search moves pos_err_rmse by ~2e-3, far above these floors.
struct Pinned {
  const char* name;
  bool larger_is_worse;
  double noise;
};
const std::vector<Pinned> kPinned = {
    {"pos_err_rmse", true, 1e-4},
    {"pos_err_p99", true, 1e-4},
    {"artifact_pct", true, 0.012},
    {"normal_err_mean_deg", true, 0.01},
    {"psnr_db", false, 0.05},
    {"fetches_mean", true, 0.01},
    {"missed_pct", true, 0.012},
    {"false_pct", true, 0.012},
    {"wrong_pct", true, 0.012},
    // What a GPU would pay (metrics/fragment_cost.h): every shaded fragment, and a warp's.
    {"frag_fetches_mean", true, 0.01},
    {"warp_fetches_mean", true, 0.01},
    {"warp_fetches_per_px", true, 0.01},
    {"iterations_mean", true, 0.01}};

TEST(Golden, TechniquesAreNoWorseThanTheirGoldenFigures) {
  const std::string path = std::string(RELIEFLAB_TEST_DIR) + "/golden/golden.json";
  const bool update = std::getenv("RELIEFLAB_UPDATE_GOLDEN") != nullptr;
  nlohmann::ordered_json golden;
  if (!update) {
    std::ifstream in(path);
    ASSERT_TRUE(in) << path << " missing: run with RELIEFLAB_UPDATE_GOLDEN=1 to create it";
    golden = nlohmann::ordered_json::parse(in);
  }
  nlohmann::ordered_json measured;
  for (const GoldenCell& c : golden_cells()) {
    SceneDesc scene = test::procedural_scene(c.kind, 64, 0.08, true);
    scene.base.kind = c.base;
    scene.effects = c.effects;
    test::Measured m = test::measure(scene, c.technique, c.params, c.view, 96);
    for (const auto& [name, value] : m.metrics.named()) measured[c.label][name] = value;
    for (const auto& [name, value] : fragment_cost(m.counts).named())
      measured[c.label][name] = value;
    if (update) continue;
    SCOPED_TRACE(c.label);
    ASSERT_TRUE(golden.contains(c.label)) << "no golden figures for this cell";
    for (const Pinned& p : kPinned) {
      const double now = measured[c.label][p.name], then = golden[c.label][p.name];
      // 1% relative, or the noise floor, whichever is larger.
      const double slack = std::max(0.01 * std::abs(then), p.noise);
      if (p.larger_is_worse)
        EXPECT_LE(now, then + slack) << p.name << " got worse: " << then << " -> " << now;
      else
        EXPECT_GE(now, then - slack) << p.name << " got worse: " << then << " -> " << now;
      const bool better = p.larger_is_worse ? now < then - slack : now > then + slack;
      if (better)
        std::printf("note: %s %s improved %g -> %g; update the golden file\n", c.label.c_str(),
                    p.name, then, now);
    }
  }
  if (update) {
    std::ofstream(path) << measured.dump(2) << "\n";
    std::printf("wrote %s\n", path.c_str());
  }
}

}  // namespace
}  // namespace rl
