// Cone step mapping's cone maps (conservative and relaxed) against brute-force scans of the
// same samples, their cache, and the relaxed search's convergence on the first hit.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

#include <gtest/gtest.h>

#include "cone_map.h"
#include "gpu/gpu_scene.h"
#include "relief/heightfield_reference.h"
#include "relief/image_io.h"
#include "relief/procedural.h"
#include "support/test_support.h"

namespace rl {
namespace {

// A procedural map of `kind` resampled to w x h and stored in 8 bits, as the cone tests read it.
ReliefMap eight_bit_map(const char* kind, int w, int h) {
  ReliefMap map = resample(make_procedural(kind, std::max(w, h), {}, 10.0, "test"), w, h);
  quantize_8bit(map);
  return map;
}

// The relaxed cone of one texel by the definition, scanned outward from its centre along every
// direction over the same samples the precompute's line sweeps read (cone_scan_directions: sub
// samples per step, bilinear, wrapping), with no block skipping, no bound from other directions
// and no hint: segment [n - 1, n] narrows the cone when h / n rises across it.
double relaxed_cone_by_scan(const ReliefMap& map, int x, int y, const ConeMapOptions& o) {
  const int side = std::max(map.width, map.height);
  const double apex = map.depth_texel(x, y);
  if (apex <= 0) return o.max_ratio;
  auto depth = [&](double X, double Y) {  // bilinear at texel-centre coordinates, wrapping
    const int x0 = int(std::floor(X)), y0 = int(std::floor(Y));
    const double ax = X - x0, ay = Y - y0;
    const double top = map.depth_texel(x0, y0) * (1 - ax) + map.depth_texel(x0 + 1, y0) * ax;
    const double bottom =
        map.depth_texel(x0, y0 + 1) * (1 - ax) + map.depth_texel(x0 + 1, y0 + 1) * ax;
    return top * (1 - ay) + bottom * ay;
  };
  double best = o.max_ratio;  // texture units across per unit depth
  for (const ConeScanDirection& d : cone_scan_directions(o.directions)) {
    const double step = d.step_texels();
    const int reach = int(std::ceil(o.max_ratio * side * apex / step)) + 2;
    double previous = depth(x + double(d.p) / d.sub, y + double(d.q) / d.sub);
    for (int n = 2; n <= reach; ++n) {
      const double h = depth(x + double(n * d.p) / d.sub, y + double(n * d.q) / d.sub);
      if (h * (n - 1) > (previous + 1e-6) * n) {  // rises by more than the precompute's tie
        if (h < apex) best = std::min(best, n * step / ((apex - h) * side));
        if (previous < apex) best = std::min(best, (n - 1) * step / ((apex - previous) * side));
      }
      previous = h;
    }
  }
  return best;
}

// A floor at depth 1 with one spike texel at depth 0: from a floor texel r texels along an
// axis, the nearest point above the floor is the spike's tip, r texels away and 1 up, so both
// cones have ratio r / side. The relaxed scan must see the tip as the end of a segment on which
// the ray from the top point leaves the spike's far side.
TEST(ConeMap, SpikeOnAFloorGivesTheDistanceToItsTip) {
  const int n = 64, sx = 20, sy = 30;
  std::vector<float> d(size_t(n) * n, 1.0f);
  d[size_t(sy) * n + sx] = 0.0f;
  const ReliefMap map = test::map_from_depths(n, n, d);
  for (bool relaxed : {false, true}) {
    ConeMapOptions o;
    o.relaxed = relaxed;
    const ConeMap c = compute_cone_map(map, o);
    for (int r = 2; r <= 12; ++r) {
      SCOPED_TRACE("relaxed " + std::to_string(relaxed) + ", r = " + std::to_string(r));
      EXPECT_NEAR(c.ratio[size_t(sy) * n + sx + r], float(r) / n, 1e-6);
      EXPECT_NEAR(c.ratio[size_t(sy + r) * n + sx], float(r) / n, 1e-6);
    }
    EXPECT_FLOAT_EQ(c.ratio[size_t(sy) * n + sx], float(o.max_ratio));  // the tip: at the top
  }
}

// Relaxed cones only drop constraints, so they are never narrower; on maps with slopes that
// face the apex they are wider. The cache returns what was computed.
TEST(ConeMap, RelaxedConesContainTheConservativeOnesAndAreCached) {
  for (const char* kind : {"pyramids", "domes", "sines"}) {
    SCOPED_TRACE(kind);
    const ReliefMap map = make_procedural(kind, 64, {}, 10.0, "test");
    ConeMapOptions o;
    o.relaxed = false;
    const ConeMap conservative = compute_cone_map(map, o);
    o.relaxed = true;
    const ConeMap relaxed = compute_cone_map(map, o);
    double sum_c = 0, sum_r = 0;
    for (size_t i = 0; i < relaxed.ratio.size(); ++i) {
      EXPECT_GE(relaxed.ratio[i], conservative.ratio[i]) << i;
      sum_c += conservative.ratio[i];
      sum_r += relaxed.ratio[i];
    }
    EXPECT_GT(sum_r, 1.1 * sum_c);
  }
  ::setenv("RELIEFLAB_CACHE_DIR", test::scratch_dir("cone_cache").c_str(), 1);
  const ReliefMap map = make_procedural("domes", 64, {}, 10.0, "test");
  const ConeMap first = cached_cone_map(map, {});
  const ConeMap second = cached_cone_map(map, {});
  EXPECT_FALSE(first.from_cache);
  EXPECT_TRUE(second.from_cache);
  EXPECT_EQ(first.ratio, second.ratio);
  ::unsetenv("RELIEFLAB_CACHE_DIR");
}

// Brute force over every texel centre of the tiled map: the conservative cone at a texel may hold
// no texel centre above its apex, ratio <= distance / (apex depth - depth) (texels across per
// unit depth, stored per longer side). A cone the shader reads (3 x 3 erosion included) that is
// wider than that lets a ray step over a feature. Small non-square 8-bit maps of every kind.
TEST(ConeMap, ConservativeConesAreNeverWiderThanBruteForce) {
  // (Before the scan held out the near texel centres, 8 of the 32 x 24 domes' 768 texels had
  // cones up to 0.11 texels per unit depth too wide, each limited by its diagonal neighbour.)
  for (const auto& [kind, w, h] :
       std::vector<std::tuple<const char*, int, int>>{{"pyramids", 32, 24},
                                                      {"domes", 32, 24},
                                                      {"sines", 32, 24},
                                                      {"bricks", 32, 24},
                                                      {"walls", 32, 24},
                                                      {"domes", 64, 40},
                                                      {"pyramids", 64, 40}}) {
    SCOPED_TRACE(std::string(kind) + " " + std::to_string(w) + "x" + std::to_string(h));
    const ReliefMap map = eight_bit_map(kind, w, h);
    ConeMapOptions o;
    o.relaxed = false;
    const ConeMap cones = compute_cone_map(map, o);
    const std::vector<float> read = ratios_safe_under_filtering(cones);
    const int side = std::max(w, h);
    int wider = 0;
    double worst = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double apex = map.depth_texel(x, y);
        double brute = o.max_ratio, at = 0;
        // Every texel centre within the cap's reach, wrapping (the map tiles).
        const int reach = int(std::ceil(o.max_ratio * side)) + 1;
        for (int dy = -reach; dy <= reach; ++dy)
          for (int dx = -reach; dx <= reach; ++dx) {
            const double rise = apex - map.depth_texel(x + dx, y + dy);
            if (rise <= 0 || (dx == 0 && dy == 0)) continue;
            if (std::hypot(dx, dy) / (rise * side) < brute) at = std::hypot(dx, dy);
            brute = std::min(brute, std::hypot(dx, dy) / (rise * side));
          }
        const double got = read[size_t(y) * w + x];
        if (got > brute + 1e-5) {
          std::printf("texel %d %d got %g brute %g at distance %g apex %g\n", x, y, got * side,
                      brute * side, at, apex);
          ++wider;
          worst = std::max(worst, (got - brute) * side);
        }
      }
    EXPECT_EQ(wider, 0) << wider << " texels' cones wider than brute force, by up to " << worst
                        << " texels per unit depth";
  }
}

// The line sweeps step over blocks, stop at the narrowest cone of the directions before and try
// a neighbour's constraint first: none of it may change a cone. Against the per-texel scan of
// the definition on small 8-bit maps of every kind, square and not, at 32 and 80 directions.
TEST(ConeMap, RelaxedConesMatchAPerTexelScanOfTheSameSamples) {
  for (const auto& [kind, w, h, directions] :
       std::vector<std::tuple<const char*, int, int, int>>{{"pyramids", 32, 32, 32},
                                                           {"domes", 32, 24, 32},
                                                           {"sines", 32, 32, 80},
                                                           {"bricks", 40, 32, 32},
                                                           {"walls", 32, 32, 32}}) {
    SCOPED_TRACE(std::string(kind) + " " + std::to_string(w) + "x" + std::to_string(h));
    const ReliefMap map = eight_bit_map(kind, w, h);
    ConeMapOptions o;
    o.directions = directions;
    const ConeMap cones = compute_cone_map(map, o);
    int off = 0;
    double worst = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double want = relaxed_cone_by_scan(map, x, y, o);
        const double got = cones.ratio[size_t(y) * w + x];
        if (std::abs(got - want) > 1e-4 * want) {
          ++off;
          worst = std::max(worst, std::abs(got - want) / want);
        }
      }
    EXPECT_EQ(off, 0) << off << " cones differ from the scan, by up to " << 100 * worst << "%";
  }
}

// The relaxed scan steps over a block of segments when every apex from its position on fails
// the segment test (relaxed_segment_left_only_before): the bound must hold for every depth pair,
// 8-bit steps and float slopes down to 1e-9 alike, and lie within three samples of where the
// test first passes, or it would step over nothing.
TEST(ConeMap, RelaxedSegmentBoundHoldsEverywhere) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), exponent(-9.0f, 0.0f);
  const size_t k = 100000;
  size_t checked = 0, tight = 0;
  for (int pair = 0; pair < 200000; ++pair) {
    const float h_start = pair % 4 ? unit(rng) : float(int(unit(rng) * 255)) / 255;
    const float rise = pair % 3 ? std::pow(10.0f, exponent(rng)) : float(1 + pair % 7) / 255;
    const float h_end = std::min(1.0f, h_start + (pair % 5 ? rise : -rise));
    const int32_t bound = relaxed_segment_left_only_before(h_start, h_end, k);
    if (bound == std::numeric_limits<int32_t>::min()) {
      for (float n : {1.0f, 2.0f, 10.0f, 1e3f, 1e5f})
        ASSERT_FALSE(relaxed_segment_leaves(h_start, h_end, n)) << h_start << " " << h_end;
      continue;
    }
    // The farthest apex the bound rules out, n samples before k; lines are never 2^22 long.
    const int64_t last = std::min<int64_t>(int64_t(k) - bound, 1 << 22);
    for (int64_t n = std::max<int64_t>(1, last - 300); n <= last; ++n, ++checked)
      ASSERT_FALSE(relaxed_segment_leaves(h_start, h_end, float(n)))
          << "h " << h_start << " -> " << h_end << ", n " << n << " (bound: n <= " << last << ")";
    if (h_end - (h_start + kRelaxedTie) >= 1e-3f) {
      EXPECT_TRUE(relaxed_segment_leaves(h_start, h_end, float(last + 3)))
          << "h " << h_start << " -> " << h_end << ": the bound is loose";
      ++tight;
    }
  }
  // Pairs whose test sits on its threshold: h_end (n0 - 1) = d n0 to within a few ulps, where
  // only the rounding of the two products decides it.
  for (int n0 = 2; n0 < 20000; n0 += 3) {
    const float h_start = unit(rng) * 0.9f, d = h_start + kRelaxedTie;
    float h_end = float(double(d) * n0 / (n0 - 1));
    for (int step = 0; step < 4; ++step) h_end = std::nextafter(h_end, 0.0f);
    for (int ulp = -4; ulp <= 4; ++ulp, h_end = std::nextafter(h_end, 2.0f)) {
      const int32_t bound = relaxed_segment_left_only_before(h_start, h_end, k);
      if (bound == std::numeric_limits<int32_t>::min()) continue;
      const int64_t last = std::min<int64_t>(int64_t(k) - bound, 1 << 22);
      for (int64_t n = std::max<int64_t>(1, last - 3); n <= last; ++n, ++checked)
        ASSERT_FALSE(relaxed_segment_leaves(h_start, h_end, float(n)))
            << "h " << h_start << " -> " << h_end << ", n " << n << " (bound: n <= " << last << ")";
    }
  }
  EXPECT_GT(checked, 1000000u);
  EXPECT_GT(tight, 10000u);
}

// A direction's scan starts from the narrowest cone the directions before it found and steps
// over what cannot narrow it further; where rounding let it step over a segment narrowing the
// cone by an ulp, the map depended on the order the cores took the directions in (the rock wall
// at 1024^2 differed from run to run). Forward, reversed and shuffled orders on one core, and the
// parallel computation, give the same map bit for bit, on the rock wall and a random map.
TEST(ConeMap, SameMapBitForBitWhateverTheOrderOfTheDirections) {
  ReliefImageSource src;
  src.depth_path = RELIEFLAB_SOURCE_DIR "/assets/relief/rockwall/rockwall_height.bmp";
  ReliefMap rock = load_relief_images(src, 10.0);
  quantize_8bit(rock);
  for (const auto& [name, map] : std::vector<std::pair<const char*, ReliefMap>>{
           {"rock", rock}, {"random", test::random_map(48, 3)}})
    for (bool relaxed : {true, false}) {
      SCOPED_TRACE(std::string(name) + (relaxed ? " relaxed" : " conservative"));
      ConeMapOptions o;
      o.relaxed = relaxed;
      std::vector<size_t> order(cone_scan_directions(o.directions).size());
      std::iota(order.begin(), order.end(), size_t(0));
      const ConeMap parallel = compute_cone_map(map, o);
      std::vector<size_t> reversed(order.rbegin(), order.rend()), shuffled = order;
      std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(7));
      for (const auto& taken : {order, reversed, shuffled}) {
        const ConeMap one_core = compute_cone_map_in_order(map, o, taken);
        size_t differing = 0;
        for (size_t i = 0; i < parallel.ratio.size(); ++i)
          differing += std::memcmp(&parallel.ratio[i], &one_core.ratio[i], sizeof(float)) != 0;
        EXPECT_EQ(differing, 0u);
      }
    }
}

// Cone stepping converges on the first hit as steps are added: on smooth 256^2 maps, 60 steps
// (and a 20-step binary search, so the last step's width does not count) find the exact hit on
// nearly every ray; 15 steps stop short on many. Measured: relaxed 60 steps 0-11 rays in 2,048
// off by more than 1e-3 in t; 15 steps 38-249.
TEST(ConeRelaxed, ConvergesOnTheFirstHitAsStepsAreAdded) {
  for (const char* kind : {"domes", "sines"}) {
    const ReliefMap map = make_procedural(kind, 256, {}, 10.0, "test");
    GpuRelief relief(map);
    for (double el : {20.0, 45.0}) {
      SCOPED_TRACE(std::string(kind) + " at " + std::to_string(int(el)) + " deg");
      const std::vector<ProbeRay> rays =
          test::as_probe_rays(test::random_tangent_rays(2048, el, el, 0.08, 7, -1e-4));
      const std::vector<ProbeHit> exact =
          test::probe("relief_exact_bilinear", {}, map, relief, rays);
      auto off = [&](int relaxed, int steps) {
        const std::vector<ProbeHit> h = test::probe(
            "cone_relaxed", {{"relaxed", relaxed}, {"cone_steps", steps}, {"binary_steps", 20}},
            map, relief, rays);
        int n = 0;
        for (size_t i = 0; i < rays.size(); ++i) n += std::abs(h[i].t - exact[i].t) > 1e-3;
        return n;
      };
      const int relaxed_15 = off(1, 15), relaxed_60 = off(1, 60), conservative_60 = off(0, 60);
      std::printf(
          "%s %2.0f deg: off by > 1e-3: relaxed 15 steps %d, 60 steps %d; conservative 60 %d\n",
          kind, el, relaxed_15, relaxed_60, conservative_60);
      EXPECT_LE(relaxed_60, 20);
      EXPECT_LT(relaxed_60, relaxed_15);
      EXPECT_LE(conservative_60, 100);
    }
  }
}

}  // namespace
}  // namespace rl
