// Safety radii and the robust binary search (Baboud & Decoret 2006, Sections 3.4-3.5).
#include <cmath>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include "../techniques/relief_robust/safety_radius.h"
#include "relief/heightfield_reference.h"
#include "relief/procedural.h"
#include "support/test_support.h"
#include "technique/gpu_scene.h"

namespace rl {
namespace {

TEST(SafetyRadius, ProfileCriterionOnHandWorkedProfiles) {
  const double inf = std::numeric_limits<double>::infinity();
  // Flat, steadily falling, and a rising bowl: no descending ray can leave the surface again.
  EXPECT_EQ(first_two_hit_distance({0, 0, 0, 0, 0, 0}, 0.5, 0), inf);
  EXPECT_EQ(first_two_hit_distance({1, 0.9, 0.8, 0.7, 0.6}, 0.5, 0), inf);
  EXPECT_EQ(first_two_hit_distance({0, 0.01, 0.04, 0.09, 0.16}, 0.5, 0), inf);
  // A bump of 0.08 after the start: a horizontal ray just above h = 0.05 at s = 1.5 passes
  // below the crest at s = 1 and is above again at 1.5.
  const std::vector<double> bump = {0, 0.05, 0.08, 0.05, 0, -0.1, -0.2, -0.3};
  EXPECT_EQ(first_two_hit_distance(bump, 0.5, 0.0), 1.5);
  // Allowing dips of 0.1 ignores the crest for horizontal rays; the first violation is then
  // a descending chord from the start to s = 2.5 (slope -0.04) under which the crest sits
  // 0.12 above -- more than the allowance.
  EXPECT_EQ(first_two_hit_distance(bump, 0.5, 0.1), 2.5);
}

ReliefMap from_depths(int n, const std::function<float(int, int)>& f) {
  std::vector<float> d;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) d.push_back(f(x, y));
  return test::map_from_depths(n, n, d);
}

TEST(SafetyRadius, FlatIsMaximalAndAFieldOfPeaksIsZero) {
  SafetyRadiusOptions o;
  SafetyRadii flat = compute_safety_radii(from_depths(16, [](int, int) { return 0.5f; }), o);
  for (uint8_t r : flat.radius) ASSERT_EQ(r, o.max_radius);
  // One-texel peaks everywhere: a ray can graze any of them twice arbitrarily close.
  SafetyRadii peaks =
      compute_safety_radii(from_depths(16, [](int x, int y) { return float((x + y) % 2); }), o);
  EXPECT_EQ(peaks.zero_count(), 16 * 16);
}

TEST(SafetyRadius, AllowingErrorOnlyGrowsRadii) {
  ReliefMap m = make_procedural("pyramids", 64, {}, 10.0, "test");
  quantize_8bit(m);
  SafetyRadii previous;
  for (double e : {0.0, 0.01, 0.05, 0.2}) {
    SafetyRadiusOptions o;
    o.error_allowed = e;
    SafetyRadii r = compute_safety_radii(m, o);
    if (!previous.radius.empty()) {
      for (size_t i = 0; i < r.radius.size(); ++i)
        ASSERT_GE(r.radius[i], previous.radius[i]) << "texel " << i;
      EXPECT_LE(r.zero_count(), previous.zero_count());
    }
    previous = r;
  }
  EXPECT_EQ(previous.zero_count(), 0);  // at 0.2 even the apexes allow a step
}

TEST(SafetyRadius, CachedOnDiskByContentAndOptions) {
  const std::string dir = test::scratch_dir("cache");
  setenv("RELIEFLAB_CACHE_DIR", dir.c_str(), 1);
  ReliefMap m = make_procedural("bricks", 32, {}, 10.0, "test");
  SafetyRadiusOptions o;
  SafetyRadii first = cached_safety_radii(m, o);
  SafetyRadii second = cached_safety_radii(m, o);
  EXPECT_FALSE(first.from_cache);
  EXPECT_TRUE(second.from_cache);
  EXPECT_EQ(first.radius, second.radius);
  o.error_allowed = 0.05;
  EXPECT_FALSE(cached_safety_radii(m, o).from_cache);
  m.relief[0].a = 0.5f;  // different content, different key
  EXPECT_FALSE(cached_safety_radii(m, SafetyRadiusOptions{}).from_cache);
  unsetenv("RELIEFLAB_CACHE_DIR");
}

// Rays whose hit differs from the reference's first hit by more than `threshold` in t.
int misses(const std::string& technique, const ParamValues& params, const ReliefMap& map,
           const std::vector<ProbeRay>& rays, double threshold, double* fetches_mean = nullptr) {
  setenv("RELIEFLAB_CACHE_DIR", test::scratch_dir("probe-cache").c_str(), 1);
  GpuRelief relief(map);
  auto t = TechniqueRegistry::instance().create(technique, params, "test");
  t->prepare(map);
  std::vector<ProbeHit> hits = t->probe(map, relief, rays, 0.08);
  int missed = 0;
  double fetches = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_TRUE(std::isfinite(hits[i].t));
    ReferenceHit ref = intersect_heightfield(map, glm::dvec3(rays[i].origin),
                                             glm::dvec3(rays[i].direction), 1.0 - rays[i].origin.z);
    missed += std::abs(hits[i].t - ref.t) > threshold;
    fetches += hits[i].fetches;
  }
  if (fetches_mean) *fetches_mean = fetches / rays.size();
  unsetenv("RELIEFLAB_CACHE_DIR");
  return missed;
}

TEST(RobustSearch, MissesFarFewerIntersectionsThanBinarySearchAtGrazingAngles) {
  // The paper's Figure 11 claim, measured on rays at 3-30 degrees over steep maps.
  for (const char* kind : {"pyramids", "bricks", "walls"}) {
    SCOPED_TRACE(kind);
    ReliefMap map = make_procedural(kind, 64, {}, 10.0, "test");
    quantize_8bit(map);
    const std::vector<ProbeRay> rays =
        test::as_probe_rays(test::random_tangent_rays(2048, 3, 30, 0.08, 17, -1e-4));
    const int binary =
        misses("relief", {{"linear_steps", 10}, {"binary_steps", 5}}, map, rays, 0.01);
    const int robust = misses("relief_robust", {}, map, rays, 0.01);
    const int exact = misses("relief_robust", {{"exact_zero_radius", 1}}, map, rays, 0.01);
    std::printf("%s: binary %d, robust %d, robust+exact %d of %zu rays missed\n", kind, binary,
                robust, exact, rays.size());
    EXPECT_LT(robust, binary / 4 + 1);
    EXPECT_LE(exact, robust);
    EXPECT_LE(exact, int(rays.size()) / 200);  // sampled directions leave a few gaps
  }
}

TEST(RobustSearch, ErrorAllowedTradesFetchesForAccuracy) {
  ReliefMap map = make_procedural("sines", 64, {}, 10.0, "test");
  quantize_8bit(map);
  const std::vector<ProbeRay> rays =
      test::as_probe_rays(test::random_tangent_rays(2048, 3, 30, 0.08, 5, -1e-4));
  double f0 = 0, f1 = 0;
  const int m0 = misses("relief_robust", {{"error_allowed", 0.0}}, map, rays, 0.01, &f0);
  const int m1 = misses("relief_robust", {{"error_allowed", 0.1}}, map, rays, 0.01, &f1);
  std::printf("error_allowed 0: %.1f fetches, %d missed; 0.1: %.1f fetches, %d missed\n", f0, m0,
              f1, m1);
  EXPECT_LT(f1, 0.8 * f0);
  EXPECT_GE(m1, m0);
}

TEST(RobustSearch, ZeroRadiusEverywhereAndAxisRaysStayBounded) {
  ReliefMap peaks = from_depths(16, [](int x, int y) { return float((x + y) % 2); });
  std::vector<ProbeRay> rays;
  for (int i = 0; i < 16; ++i) {
    const float c = (i + 0.5f) / 16;
    rays.push_back({glm::vec3(c, 0.3f, -1e-4f), glm::vec3(2.0f, 0.0f, 1.0f)});   // v component 0
    rays.push_back({glm::vec3(0.3f, c, -1e-4f), glm::vec3(0.0f, -2.0f, 1.0f)});  // u component 0
    rays.push_back({glm::vec3(c, c, -1e-4f), glm::vec3(0.0f, 0.0f, 1.0f)});      // vertical
    rays.push_back({glm::vec3(0.0f, c, -1e-4f), glm::vec3(-3.0f, 1.0f, 1.0f)});  // border texel
  }
  for (double exact : {0.0, 1.0}) {
    setenv("RELIEFLAB_CACHE_DIR", test::scratch_dir("zero").c_str(), 1);
    GpuRelief relief(peaks);
    auto t = TechniqueRegistry::instance().create("relief_robust", {{"exact_zero_radius", exact}},
                                                  "test");
    t->prepare(peaks);
    std::vector<ProbeHit> hits = t->probe(peaks, relief, rays, 0.08);
    for (size_t i = 0; i < rays.size(); ++i) {
      SCOPED_TRACE("ray " + std::to_string(i) + (exact ? " exact" : " clamp"));
      ASSERT_TRUE(std::isfinite(hits[i].t) && std::isfinite(hits[i].uv.x));
      EXPECT_TRUE(hits[i].hit);
      // Every column costs a radius fetch and a depth fetch (or one gather per cell), plus
      // the binary search: bounded by the ray's length in texels.
      const glm::vec3 d = rays[i].direction;
      EXPECT_LE(hits[i].fetches, int(3 * (std::abs(d.x) + std::abs(d.y)) * 16) + 8 + 4);
      if (exact) {
        ReferenceHit ref =
            intersect_heightfield(peaks, glm::dvec3(rays[i].origin), glm::dvec3(d), 1.0);
        EXPECT_NEAR(hits[i].t, ref.t, 1e-4);
      }
    }
    unsetenv("RELIEFLAB_CACHE_DIR");
  }
}

}  // namespace
}  // namespace rl
