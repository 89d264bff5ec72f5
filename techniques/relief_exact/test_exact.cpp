// Baboud & Decoret's exact traversal and ReliefLab's exact bilinear traversal, in ray-probe
// mode against the double-precision reference (the same bilinear surface, solved exactly).
#include <cmath>

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>
#include "relief/window_pyramid.h"

#include "gpu/gpu_scene.h"
#include "relief/heightfield_reference.h"
#include "relief/procedural.h"
#include "support/test_support.h"

namespace rl {
namespace {

ReliefMap from_depths(int w, int h, const std::vector<float>& d) {
  return test::map_from_depths(w, h, d);
}

// Saddles everywhere: a checker of 0 and 1 (every cell's twist is 2).
ReliefMap checker(int n) {
  std::vector<float> d;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) d.push_back(float((x + y) % 2));
  return from_depths(n, n, d);
}

struct Comparison {
  int rays = 0, missed = 0;  // missed: the hit is not the reference's first crossing
  double max_residual = 0;   // worst |ray depth - surface depth| at the hit, over rays not missed
  double max_residual_bound = 0;
};

// Float-level bound on the residual of a hit found with float32 arithmetic: the walk's
// coordinates reach (1 + lateral texels travelled) in magnitude, each carries a relative
// rounding of 2^-24 a few times over, and depth changes by at most 1 per texel (maps are in
// [0, 1]). Near-tangent rays are ill-conditioned in t, so t itself is not the yardstick: the
// residual is (backward error), together with finding the first crossing (no miss).
double float_level(const ProbeRay& r, double t, int size) {
  const double lateral = (std::abs(r.direction.x) + std::abs(r.direction.y)) * size * t;
  return 16.0 * std::ldexp(1.0, -24) * (size + lateral) + 1e-6;
}

Comparison compare(const std::string& technique, const ReliefMap& map,
                   const std::vector<ProbeRay>& rays, double miss_threshold) {
  GpuRelief relief(map);
  auto t = TechniqueRegistry::instance().create(technique, {}, "test");
  std::vector<ProbeHit> hits = t->probe(map, relief, rays, glm::dvec2(0.08));
  Comparison c;
  std::printf("%s on %dx%d: ", technique.c_str(), map.width, map.height);
  for (size_t i = 0; i < rays.size(); ++i) {
    const glm::dvec3 o(rays[i].origin), d(rays[i].direction);
    ReferenceHit ref = intersect_heightfield(map, o, d, 1.0 - o.z);
    EXPECT_TRUE(ref.hit);
    EXPECT_TRUE(std::isfinite(hits[i].t));
    ++c.rays;
    if (std::abs(hits[i].t - ref.t) > miss_threshold) {
      ++c.missed;
      continue;
    }
    const double th = hits[i].t;
    const double residual =
        std::abs(o.z + d.z * th - map.sample_depth(o.x + d.x * th, o.y + d.y * th));
    const double bound = float_level(rays[i], th, map.width);
    if (residual / bound > c.max_residual / std::max(c.max_residual_bound, 1e-30)) {
      c.max_residual = residual;
      c.max_residual_bound = bound;
    }
  }
  std::printf("%d rays, %d missed, worst residual %.3g (float-level bound there %.3g)\n", c.rays,
              c.missed, c.max_residual, c.max_residual_bound);
  return c;
}

// The techniques that solve every cell they reach exactly: each must find the reference's
// first crossing on every ray.
const char* const kExactBilinear[] = {"relief_exact_bilinear", "relief_hierarchical_exact",
                                      "relief_window_exact"};

TEST(ExactBilinear, MatchesTheReferenceAtFloatLevelOnAdversarialSaddles) {
  for (const char* technique : kExactBilinear)
    for (int n : {4, 16}) {
      SCOPED_TRACE(n);
      Comparison c = compare(
          technique, checker(n),
          test::as_probe_rays(test::random_tangent_rays(4096, 2, 85, 0.08, 1, -1e-4)), 1e-3);
      EXPECT_EQ(c.missed, 0);
      EXPECT_LE(c.max_residual, c.max_residual_bound);
    }
}

TEST(ExactBilinear, MatchesTheReferenceOnRandomAndProceduralMaps) {
  const std::vector<std::pair<std::string, ReliefMap>> maps = {
      {"random", test::random_map(32, 5)},
      {"bricks", make_procedural("bricks", 64, {}, 10.0, "test")},
      {"pyramids", make_procedural("pyramids", 64, {}, 10.0, "test")},
      {"walls", make_procedural("walls", 64, {{"spacing", 8}}, 10.0, "test")}};
  for (const char* technique : kExactBilinear)
    for (const auto& [name, map] : maps) {
      SCOPED_TRACE(name);
      Comparison c = compare(
          technique, map,
          test::as_probe_rays(test::random_tangent_rays(4096, 2, 85, 0.08, 2, -1e-4)), 1e-3);
      EXPECT_EQ(c.missed, 0);
      EXPECT_LE(c.max_residual, c.max_residual_bound);
    }
}

// Every value of the window pyramid bounds, from above, every cell a step of at most b texels
// from any point of its block can reach, for each way of moving along each axis (0: either):
// brute force over the points' possible cells, the window's edges given half a texel to spare.
TEST(WindowPyramid, EveryValueBoundsTheCellsAStepCanReach) {
  const int W = 32, H = 16;
  std::vector<float> cells(size_t(W) * H);
  uint32_t state = 12345;
  for (float& c : cells) c = float((state = state * 1664525u + 1013904223u) >> 8) / 16777216.0f;
  // Cells floor(X) a step can reach from X = u W - 0.5 in block I (X in [I b - 0.5, (I + 1) b
  // - 0.5)), half a texel further each side.
  auto reach = [](int I, int b, int way) {
    const double lo = I * b - 0.5 - 0.5 - (way > 0 ? 0 : b);
    const double hi = (I + 1) * b - 0.5 + 0.5 + (way < 0 ? 0 : b);
    return std::pair<int, int>(int(std::floor(lo)), int(std::ceil(hi)) - 1);
  };
  for (int way_x : {0, 1, -1})
    for (int way_y : {0, 1, -1})
      for (int b : {1, 2, 4, 8}) {
        SCOPED_TRACE(testing::Message() << "b " << b << " ways " << way_x << "," << way_y);
        const std::vector<float> level = window_level(cells, W, H, b, way_x, way_y);
        ASSERT_EQ(level.size(), size_t(W / b) * (H / b));
        for (int J = 0; J < H / b; ++J)
          for (int I = 0; I < W / b; ++I) {
            const auto [x0, x1] = reach(I, b, way_x);
            const auto [y0, y1] = reach(J, b, way_y);
            float least = 2.0f;
            for (int y = y0; y <= y1; ++y)
              for (int x = x0; x <= x1; ++x)
                least =
                    std::min(least, cells[size_t((y % H + H) % H) * W + size_t((x % W + W) % W)]);
            EXPECT_LE(level[size_t(J) * (W / b) + I], least) << I << "," << J;
          }
      }
  // A window for one way is tighter than the one for either: on this map, strictly so somewhere.
  EXPECT_NE(window_level(cells, W, H, 4, 1, 1), window_level(cells, W, H, 4, 0, 0));
}

TEST(Exact, MissesSaddlesThatTheBilinearWalkFinds) {
  // The paper's Figure 3: between two centerline crossings above the surface, a ray can dip
  // below a saddle; linear profiles cannot see it. On a checker of saddles some rays do.
  ReliefMap map = checker(8);
  std::vector<ProbeRay> rays =
      test::as_probe_rays(test::random_tangent_rays(4096, 2, 60, 0.08, 3, -1e-4));
  Comparison exact = compare("relief_exact", map, rays, 1e-3);
  Comparison bilinear = compare("relief_exact_bilinear", map, rays, 1e-3);
  EXPECT_GT(exact.missed, 0);
  EXPECT_EQ(bilinear.missed, 0);
  // On maps whose cells are planar along the ray (a linear ramp), the linear profiles are exact.
  std::vector<float> ramp;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) ramp.push_back(0.2f + 0.6f * float(y) / 15.0f);
  std::vector<ProbeRay> along;
  for (int i = 0; i < 64; ++i)
    along.push_back({glm::vec3(0.1f + 0.01f * i, 0.3f, -1e-4f), glm::vec3(0.3f, 0.0f, 1.0f)});
  Comparison planar = compare("relief_exact", from_depths(16, 16, ramp), along, 1e-3);
  EXPECT_EQ(planar.missed, 0);
  EXPECT_LE(planar.max_residual, planar.max_residual_bound);
}

TEST(Exact, HardCasesStayFiniteAndBounded) {
  // A single one-texel spike, full-range depth discontinuities, rays along the texel axes
  // (direction components of exactly 0), on border texels, and grazing a plateau at its height.
  std::vector<float> spike(32 * 32, 1.0f);
  spike[10 * 32 + 10] = 0.0f;
  std::vector<float> step;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) step.push_back(x < 16 ? 0.0f : 1.0f);
  std::vector<ProbeRay> rays;
  for (int i = 0; i < 32; ++i) {
    const float c = (i + 0.5f) / 32.0f;
    rays.push_back({glm::vec3(c, 10.5f / 32, -1e-4f), glm::vec3(0.9f, 0.0f, 1.0f)});   // +u only
    rays.push_back({glm::vec3(10.5f / 32, c, -1e-4f), glm::vec3(0.0f, -0.9f, 1.0f)});  // -v only
    rays.push_back({glm::vec3(c, c, -1e-4f), glm::vec3(0.0f, 0.0f, 1.0f)});            // vertical
    rays.push_back({glm::vec3(0.0f, c, -1e-4f), glm::vec3(-0.5f, 0.25f, 1.0f)});  // border texel
    rays.push_back({glm::vec3(c, 1.0f, 0.0f), glm::vec3(40.0f, 0.0f, 1.0f)});     // on the plateau
  }
  for (const char* technique : {"relief_exact", "relief_exact_bilinear"}) {
    for (const auto& map : {from_depths(32, 32, spike), from_depths(32, 32, step)}) {
      GpuRelief relief(map);
      auto t = TechniqueRegistry::instance().create(technique, {}, "test");
      std::vector<ProbeHit> hits = t->probe(map, relief, rays, glm::dvec2(0.08));
      for (size_t i = 0; i < rays.size(); ++i) {
        SCOPED_TRACE(std::string(technique) + " ray " + std::to_string(i));
        ASSERT_TRUE(std::isfinite(hits[i].t) && std::isfinite(hits[i].uv.x) &&
                    std::isfinite(hits[i].uv.y));
        EXPECT_TRUE(hits[i].hit);
        // One fetch per centerline crossed, + the entry sample: bounded by the ray's length.
        const glm::vec3 d = rays[i].direction;
        EXPECT_LE(hits[i].fetches,
                  int((std::abs(d.x) + std::abs(d.y)) * 32 * (1 - rays[i].origin.z)) + 3);
        ReferenceHit ref = intersect_heightfield(map, glm::dvec3(rays[i].origin), glm::dvec3(d),
                                                 1.0 - rays[i].origin.z);
        if (std::string(technique) == "relief_exact_bilinear") {
          EXPECT_NEAR(hits[i].t, ref.t, 1e-4);
        }
      }
    }
  }
}

TEST(ExactBilinear, ImageErrorIsAtTheTruthsTessellationLevel) {
  // Against a truth tessellated to within 1e-4 depth units of the bilinear surface, the
  // bilinear walk's hits are as close as that truth on all but the rare pixels whose ray
  // grazes a ridge (where a 1e-4 difference flips the hit to what lies behind it).
  SceneDesc scene = test::procedural_scene("pyramids", 32, 0.08, true, {{"count", 4}});
  const double tolerance = 1e-4;
  const double el = 35, fov_half = 20;
  test::Measured b =
      test::measure(scene, "relief_exact_bilinear", {}, View{el, 25}, 128, tolerance);
  test::Measured e = test::measure(scene, "relief_exact", {}, View{el, 25}, 128, tolerance);
  EXPECT_EQ(b.metrics.at("nonfinite_px"), 0);
  EXPECT_EQ(b.metrics.at("missed_pct"), 0);
  // A vertical surface deviation of 1e-4 moves a hit along the ray by at most 1e-4 / sin(e)
  // at local elevation e >= el - fov/2 (slopes make it smaller, not larger, on these rays).
  const double along_ray = tolerance / std::sin(glm::radians(el - fov_half));
  EXPECT_LE(b.metrics.at("pos_err_p99"), along_ray + 1e-5);
  EXPECT_LE(b.metrics.at("artifact_pct"), 0.05);
  // The linear-profile walk is measurably less exact on the same pixels.
  EXPECT_GT(e.metrics.at("pos_err_p99"), b.metrics.at("pos_err_p99"));
}

}  // namespace
}  // namespace rl
