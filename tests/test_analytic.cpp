// Analytic scenes with exact answers, through the whole pipeline (GL render vs Embree truth).
#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "support/test_support.h"

namespace rl {
namespace {

using test::measure;
using test::procedural_scene;

// Rasterised coverage and the truth's pixel-centre rays agree except, at most, on pixels
// whose centre lies on the quad's edge.
constexpr double kEdgeCoveragePct = 0.5;

// Largest colour difference over pixels both cover (edge pixels differ by coverage alone).
double max_joint_color_error(const test::Measured& m) {
  double worst = 0;
  for (size_t i = 0; i < m.truth.size(); ++i)
    if (m.truth.covered(i) && m.technique.covered(i))
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, double(std::abs(m.truth.color[i][c] - m.technique.color[i][c])));
  return worst;
}

TEST(Analytic, FlatMapEveryTechniqueHitsTheBaseExactly) {
  SceneDesc scene = procedural_scene("flat", 32);
  // Relief with 20 binary steps: its interval, (1/10) / 2^19 depth units, is below float noise.
  const std::vector<std::pair<std::string, ParamValues>> runs = {
      {"normal", {}}, {"parallax", {}}, {"relief", {{"linear_steps", 10}, {"binary_steps", 20}}}};
  for (const auto& [t, params] : runs) {
    test::Measured m = measure(scene, t, params, View{40, 25});
    SCOPED_TRACE(t);
    EXPECT_GT(m.metrics.at("covered_px"), 2000);
    EXPECT_LE(m.metrics.at("missed_pct") + m.metrics.at("false_pct"), kEdgeCoveragePct);
    EXPECT_LE(m.metrics.at("pos_err_max"), 1e-4);  // depth units: float rounding only
    EXPECT_EQ(m.metrics.at("artifact_pct"), 0);
    EXPECT_LT(m.metrics.at("normal_err_mean_deg"), 0.01);
    EXPECT_LT(max_joint_color_error(m), 2e-3);  // same texels, same shading formula
  }
}

TEST(Analytic, ReliefBinarySearchStopsBelowTheSurface) {
  // Listing 5.3's binary search keeps the last point found inside, never the crossing itself:
  // with L linear and B binary steps it ends (1/L) / 2^(B-1) depth units below a flat top.
  // Along a ray at local elevation e that is a distance of that depth / sin(e).
  SceneDesc scene = procedural_scene("flat", 32);
  test::Measured m =
      measure(scene, "relief", {{"linear_steps", 10}, {"binary_steps", 5}}, View{40, 25});
  const double depth_error = 0.1 / 16;
  const double min_local_elevation = glm::radians(40.0 - 20.0);  // half the 40-degree fov
  EXPECT_GE(m.metrics.at("pos_err_mean"), depth_error);
  EXPECT_LE(m.metrics.at("pos_err_max"), depth_error / std::sin(min_local_elevation));
}

TEST(Analytic, ConstantDepthIsHitOnItsPlane) {
  SceneDesc scene = procedural_scene("constant", 32, 0.08, false, {{"value", 0.5}});
  // The truth lies on z = -0.5 * depth.
  test::Measured relief =
      measure(scene, "relief", {{"linear_steps", 16}, {"binary_steps", 8}}, View{50, 10});
  for (size_t i = 0; i < relief.truth.size(); ++i)
    if (relief.truth.covered(i)) {
      ASSERT_NEAR(relief.truth.position[i].z, -0.04, 1e-6);
    }
  // Relief mapping ends within its binary interval: (1 / 16) / 2^8 depth units (+ float).
  EXPECT_LE(relief.metrics.at("pos_err_max"), 1.0 / 16 / 256 + 1e-4);
  // Kaneko's parallax (no offset limiting) reaches the view ray at the fragment's depth,
  // which is exact for a constant depth.
  test::Measured parallax = measure(scene, "parallax", {{"offset_limiting", 0}}, View{50, 10});
  EXPECT_LE(parallax.metrics.at("pos_err_max"), 1e-4);
  // Normal mapping shades the base, half the relief depth above the truth.
  test::Measured normal = measure(scene, "normal", {}, View{50, 10});
  EXPECT_GE(normal.metrics.at("pos_err_mean"), 0.5);
  EXPECT_EQ(normal.metrics.at("artifact_pct"), 100);
}

TEST(Analytic, FetchCountsAreWhatTheListingsSay) {
  SceneDesc scene = procedural_scene("flat", 32);
  // Normal mapping: normal + colour. Parallax: + one depth fetch.
  EXPECT_EQ(measure(scene, "normal", {}, View{60, 0}).metrics.at("fetches_max"), 2);
  EXPECT_EQ(measure(scene, "parallax", {}, View{60, 0}).metrics.at("fetches_max"), 3);
  // Relief on a flat map: the first linear step is inside, then every binary step, + 2.
  test::Measured r =
      measure(scene, "relief", {{"linear_steps", 8}, {"binary_steps", 5}}, View{60, 0});
  EXPECT_EQ(r.metrics.at("fetches_mean"), 1 + 5 + 2);
  EXPECT_EQ(r.metrics.at("fetches_max"), 1 + 5 + 2);
}

}  // namespace
}  // namespace rl
