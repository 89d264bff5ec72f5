// The cost a GPU would pay (metrics/fragment_cost.h): fetches per shaded fragment, discarded
// ones included, and the lockstep cost of 2 x 2 quads and 8 x 4 warps, pinned on counts with
// closed-form answers and on frames whose every lane is known; and the search iterations beside
// them.
#include <cmath>

#include <gtest/gtest.h>

#include "metrics/fragment_cost.h"
#include "support/test_support.h"

namespace rl {
namespace {

// One fragment per pixel, every one fetching `fetches`.
FragmentCounts uniform_counts(int w, int h, uint32_t fetches) {
  FragmentCounts c;
  c.resize(w, h);
  for (size_t i = 0; i < c.fragments.size(); ++i) {
    c.fragments[i] = 1;
    c.fetch_sum[i] = fetches;
    c.fetch_max[i] = fetches;
  }
  return c;
}

TEST(FragmentCost, EveryLaneEqualCostsTheMean) {
  const FragmentCost cost = fragment_cost(uniform_counts(16, 8, 7));
  EXPECT_EQ(cost.fragments, 128);
  EXPECT_EQ(cost.frag_fetches_mean, 7);
  EXPECT_EQ(cost.frag_fetches_max, 7);
  EXPECT_EQ(cost.quad_fetches_mean, 7);
  EXPECT_EQ(cost.warp_fetches_mean, 7);
  EXPECT_EQ(cost.warp_fetches_per_px, 7);
}

TEST(FragmentCost, OneDeepPitCostsItsWholeWarp) {
  // 16 x 8 pixels: four 8 x 4 warps, 32 quads. Pixel (3, 1) walks 50 fetches, the rest 5.
  FragmentCounts c = uniform_counts(16, 8, 5);
  const size_t pit = 1 * 16 + 3;
  c.fetch_sum[pit] = c.fetch_max[pit] = 50;
  const FragmentCost cost = fragment_cost(c);
  EXPECT_DOUBLE_EQ(cost.frag_fetches_mean, (127 * 5 + 50) / 128.0);
  // Its warp: 32 lanes at 50; three warps at 5.
  EXPECT_DOUBLE_EQ(cost.warp_fetches_mean, (32 * 50 + 3 * 32 * 5) / 128.0);  // 16.25
  // Its quad: 4 lanes at 50; 31 quads at 5.
  EXPECT_DOUBLE_EQ(cost.quad_fetches_mean, (4 * 50 + 31 * 4 * 5) / 128.0);  // 6.40625
  EXPECT_EQ(cost.frag_fetches_max, 50);
}

TEST(FragmentCost, PassesPoolPerPixelAndEmptyPixelsCostNothing) {
  // 10 x 5: tiles cut at the frame's edge. Pixel (0, 0) shaded twice (two passes: 4 and 8
  // fetches), pixel (9, 4) once with 3, the rest never.
  FragmentCounts c;
  c.resize(10, 5);
  c.fragments[0] = 2, c.fetch_sum[0] = 12, c.fetch_max[0] = 8;
  const size_t corner = 4 * 10 + 9;
  c.fragments[corner] = 1, c.fetch_sum[corner] = 3, c.fetch_max[corner] = 3;
  const FragmentCost cost = fragment_cost(c);
  EXPECT_EQ(cost.fragments, 3);
  EXPECT_DOUBLE_EQ(cost.frag_fetches_mean, 15 / 3.0);
  // Pixel (0, 0)'s tile: 2 fragments at its slowest 8; the corner's tile: 1 at 3.
  EXPECT_DOUBLE_EQ(cost.warp_fetches_mean, (2 * 8 + 1 * 3) / 3.0);
  EXPECT_DOUBLE_EQ(cost.quad_fetches_mean, (2 * 8 + 1 * 3) / 3.0);
  // Per pixel drawn: the same total over the 2 pixels shaded (both passes charged to one).
  EXPECT_DOUBLE_EQ(cost.warp_fetches_per_px, (2 * 8 + 1 * 3) / 2.0);
}

TEST(FragmentCost, EveryPassOfAMultiPassTechniqueIsPaidPerPixel) {
  // Depth slicing draws one quad per slice: per fragment it costs what one slice does, per
  // pixel it pays every slice (Listing 5.2; each slice's fragment reads the map once or twice).
  SceneDesc scene = test::procedural_scene("bricks", 64, 0.08, false);
  for (int slices : {16, 32}) {
    const test::Measured m =
        test::measure(scene, "depth_slicing", {{"slices", slices}}, View{90, 0}, 32);
    const FragmentCost cost = fragment_cost(m.counts);
    SCOPED_TRACE(slices);
    ASSERT_GT(cost.fragments, 0);
    EXPECT_LE(cost.warp_fetches_mean, 2.0);  // one slice's fragment, slowest lane
    EXPECT_GE(cost.warp_fetches_per_px, slices * 1.0);
    EXPECT_GE(cost.warp_fetches_per_px, m.metrics.at("fetches_mean"));
  }
}

TEST(FragmentCost, IterationsAreCountedPerShadedFragment) {
  // Two pixels: one shaded twice (passes of 6 and 2 iterations), one once with 9; a third
  // never shaded keeps stale-looking counts that must not count.
  FragmentCounts c;
  c.resize(4, 1);
  c.fragments[0] = 2, c.iteration_sum[0] = 8, c.iteration_max[0] = 6;
  c.fragments[1] = 1, c.iteration_sum[1] = 9, c.iteration_max[1] = 9;
  c.iteration_sum[2] = 100, c.iteration_max[2] = 100;
  const FragmentCost cost = fragment_cost(c);
  EXPECT_DOUBLE_EQ(cost.iterations_mean, 17 / 3.0);
  EXPECT_EQ(cost.iterations_max, 9);
}

TEST(FragmentCost, NothingShadedIsNotMeasured) {
  FragmentCounts c;
  c.resize(8, 4);
  const FragmentCost cost = fragment_cost(c);
  EXPECT_EQ(cost.fragments, 0);
  EXPECT_TRUE(std::isnan(cost.frag_fetches_mean));
  EXPECT_TRUE(std::isnan(cost.warp_fetches_mean));
  EXPECT_TRUE(std::isnan(cost.warp_fetches_per_px));
  EXPECT_TRUE(std::isnan(cost.iterations_mean));
  EXPECT_TRUE(std::isnan(cost.iterations_max));
}

TEST(FragmentCost, AFlatMapCostsEveryLaneTheSame) {
  // A constant map seen straight down: relief's linear search stops at the same step on every
  // pixel, so every quad and warp costs the mean, which is the covered pixels' mean.
  SceneDesc scene = test::procedural_scene("constant", 64, 0.08, false, {{"value", 0.5}});
  const test::Measured m = test::measure(scene, "relief", {}, View{90, 0}, 64);
  const FragmentCost cost = fragment_cost(m.counts);
  ASSERT_GT(cost.fragments, 0);
  EXPECT_EQ(cost.frag_fetches_max, cost.frag_fetches_mean);
  EXPECT_EQ(cost.warp_fetches_mean, cost.frag_fetches_mean);
  EXPECT_EQ(cost.quad_fetches_mean, cost.frag_fetches_mean);
  EXPECT_DOUBLE_EQ(cost.frag_fetches_mean, m.metrics.at("fetches_mean"));
  // Listing 5.3 at its defaults (10 linear, 5 binary): depth 0.5 is reached at step 5, then 5
  // bisections, + normal and colour.
  EXPECT_EQ(cost.frag_fetches_mean, 5 + 5 + 2);
  // Iterations: the same 5 linear and 5 binary steps; the shading fetches are no iteration.
  EXPECT_EQ(cost.iterations_mean, 5 + 5);
  EXPECT_EQ(cost.iterations_max, 5 + 5);
}

TEST(FragmentCost, ATechniqueWithoutASearchIteratesNothing) {
  SceneDesc scene = test::procedural_scene("domes", 32, 0.08, false);
  const test::Measured m = test::measure(scene, "normal", {}, View{45, 0}, 32);
  const FragmentCost cost = fragment_cost(m.counts);
  ASSERT_GT(cost.fragments, 0);
  EXPECT_EQ(cost.iterations_max, 0);
  EXPECT_GT(cost.frag_fetches_mean, 0);
}

TEST(FragmentCost, MissedRaysUnderABoxProxyAreCharged) {
  // Domes on an empty floor under the box proxy: the rays between the domes walk to the floor
  // and are discarded. They cost the GPU their walk; the covered pixels' mean leaves them out.
  SceneDesc scene = test::procedural_scene("domes", 64, 0.25, true);
  scene.proxy = Proxy::Box;
  scene.empty_floor = true;
  const test::Measured m = test::measure(scene, "relief_exact_bilinear", {}, View{20, 30}, 64);
  const FragmentCost cost = fragment_cost(m.counts);
  long covered = 0;
  for (size_t i = 0; i < m.technique.size(); ++i) covered += m.technique.covered(i);
  EXPECT_GT(cost.fragments, covered + 100) << "discarded fragments are counted";
  EXPECT_GT(cost.frag_fetches_mean, m.metrics.at("fetches_mean"));
  // An exact walk's per-pixel work varies: a warp waits for its longest walk.
  EXPECT_GT(cost.warp_fetches_mean, cost.quad_fetches_mean);
  EXPECT_GT(cost.quad_fetches_mean, cost.frag_fetches_mean);
}

}  // namespace
}  // namespace rl
