// The bounding-box proxy (Baboud & Decoret, Section 3): silhouettes come from the search.
#include <gtest/gtest.h>

#include "support/test_support.h"

namespace rl {
namespace {

SceneDesc box_scene(const std::string& kind, const std::map<std::string, double>& options = {}) {
  SceneDesc s = test::procedural_scene(kind, 32, 0.25, true, options);
  s.proxy = Proxy::Box;
  return s;
}

TEST(BoxProxy, AFullBoxIsDrawnWithItsWalls) {
  // Depth 0 everywhere: the relief is the whole box, side walls included. Every technique
  // that can draw the box enters through the walls below the surface and stops there.
  for (const char* t : {"relief_exact_bilinear", "relief_exact", "relief_robust", "relief"}) {
    SCOPED_TRACE(t);
    test::Measured m = test::measure(box_scene("flat"), t, {}, View{30, 30}, 96);
    EXPECT_GT(m.metrics.at("covered_px"), 1500);
    EXPECT_LE(m.metrics.at("missed_pct") + m.metrics.at("false_pct"), 0.5);  // edge pixels only
    // The exact walks stop on the surface; the binary searches within their last interval
    // (relief: (1/10)/2^4 depth units along the ray; robust: a 16-texel step halved 8 times).
    const bool exact = std::string(t).find("exact") != std::string::npos;
    EXPECT_LE(m.metrics.at("pos_err_p99"), exact ? 1e-3 : 0.05);
  }
}

TEST(BoxProxy, SilhouettesOfPeaksComeFromTheSearch) {
  // Pyramids seen at 20 degrees: their tips make the silhouette. The exact walk reproduces
  // the truth's coverage; a coarse binary search cuts the tips off (the paper's Figure 11).
  SceneDesc scene = box_scene("pyramids", {{"count", 4}});
  test::Measured exact = test::measure(scene, "relief_exact_bilinear", {}, View{20, 30}, 128);
  test::Measured binary = test::measure(
      scene, "relief", {{"linear_steps", 10}, {"binary_steps", 5}}, View{20, 30}, 128);
  EXPECT_LE(exact.metrics.at("missed_pct") + exact.metrics.at("false_pct"), 0.1);
  EXPECT_GT(binary.metrics.at("missed_pct"), 10 * std::max(exact.metrics.at("missed_pct"), 0.01));
  // Background exists: rays that pass between the peaks leave the box.
  EXPECT_LT(exact.metrics.at("covered_px"), 128 * 128);
}

}  // namespace
}  // namespace rl
