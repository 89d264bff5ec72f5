// Omni-directional displacement maps (chapter 5, Listing 5.9): the chapter's angle formulas
// invert its ray directions and stay finite at their ends (acos at exactly +-1 and past it by
// rounding, the pole where a is undefined); the 4D map is exact on stored rays (a stored
// direction from a super pixel's centre) and its error grows between them; whole frames are
// finite at elevations 90 and 0.
#include <gtest/gtest.h>

#include <cmath>

#include "gl/context.h"
#include "gpu/gpu_scene.h"
#include "odd_map.h"
#include "scene/relief_asset.h"
#include "support/test_support.h"
#include "truth/heightfield_truth.h"

namespace rl {
namespace {

TEST(Odd, AnglesInvertTheChaptersDirectionsAndStayFiniteAtTheirEnds) {
  for (int i = 0; i <= 16; ++i)
    for (int j = 1; j < 16; ++j) {  // b = 0 or pi: the pole, where every a is one direction
      const double a = M_PI * i / 16, b = M_PI * j / 16;
      const glm::dvec2 ab = OddMap::angles(OddMap::direction(a, b));
      EXPECT_NEAR(ab.x, a / M_PI, 1e-6) << i << " " << j;
      EXPECT_NEAR(ab.y, b / M_PI, 1e-9) << i << " " << j;
    }
  // Past the acos domain by rounding, and the pole itself.
  for (const glm::dvec3& v :
       {glm::dvec3(1 + 1e-12, 0, 0), glm::dvec3(-1 - 1e-12, 0, 0), glm::dvec3(0, 1 + 1e-12, 0),
        glm::dvec3(0, -1, 0), glm::dvec3(1e-30, 1, 0)}) {
    const glm::dvec2 ab = OddMap::angles(v);
    EXPECT_TRUE(std::isfinite(ab.x) && std::isfinite(ab.y));
    EXPECT_GE(ab.x, 0.0);
    EXPECT_LE(ab.x, 1.0);
  }
  EXPECT_EQ(OddMap::angles({0, 1, 0}).x, 0.5);  // along the binormal: a = pi / 2
}

struct OddProbe {
  ReliefMap map;
  std::unique_ptr<GpuRelief> gpu;
  std::unique_ptr<Technique> technique;
};

OddProbe odd_on_sines(int spatial, int directions, bool interpolate) {
  GlContext::shared();
  OddProbe p;
  p.map = build_relief_asset(test::procedural_scene("sines", 64, 0.08, true), 64);
  p.gpu = std::make_unique<GpuRelief>(p.map);
  p.technique = TechniqueRegistry::instance().create(
      "odd",
      {{"spatial", spatial}, {"directions", directions}, {"interpolate", double(interpolate)}},
      "test");
  return p;
}

// Mean |depth error| of the 4D map's answers against the surface itself, on probe rays from
// the centres of super pixels (offset by `spatial_offset` super pixels) in stored directions
// (offset by `direction_offset` grid cells in a and b).
double mean_depth_error(OddProbe& p, int spatial, int directions, double spatial_offset,
                        double direction_offset) {
  const glm::dvec2 aspect(0.3, 0.3);  // world depth over the tile's world side
  const HeightfieldTruth truth(p.map, 1e-3);
  std::vector<ProbeRay> rays;
  std::vector<double> expected;
  for (int y = 0; y < spatial; y += 3)
    for (int x = 0; x < spatial; x += 3)
      for (int kb = 1; kb + 1 < directions; ++kb)
        for (int ka = 1; ka + 1 < directions; ++ka) {
          const glm::dvec3 r = OddMap::direction(M_PI * (ka + 0.5 + direction_offset) / directions,
                                                 M_PI * (kb + 0.5 + direction_offset) / directions);
          const glm::dvec3 o((x + 0.5 + spatial_offset) / spatial,
                             (y + 0.5 + spatial_offset) / spatial, kOddStartDepth);
          const glm::dvec3 d(r.x * aspect.x / r.z, r.y * aspect.y / r.z, 1);
          const TruthHit h = truth.intersect(o, d, 0, 1 - kOddStartDepth + 1e-6);
          if (!h.hit) continue;
          rays.push_back({glm::vec3(o.x, o.y, 0.0), glm::vec3(d)});
          expected.push_back(h.point.z);
        }
  const std::vector<ProbeHit> hits = p.technique->probe(p.map, *p.gpu, rays, aspect);
  double sum = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_TRUE(std::isfinite(hits[i].depth));
    sum += std::abs(hits[i].depth - expected[i]);
  }
  return sum / double(rays.size());
}

TEST(Odd, ExactOnStoredRaysAndWorseBetweenThem) {
  // Stored rays come back to within the 8-bit depth (half a step, 0.002) and the truth's 1e-3
  // tolerance; half a direction cell or half a super pixel away the answer is a neighbour's.
  OddProbe p = odd_on_sines(16, 8, false);
  const double on = mean_depth_error(p, 16, 8, 0, 0);
  const double between_directions = mean_depth_error(p, 16, 8, 0, 0.5);
  const double between_points = mean_depth_error(p, 16, 8, 0.5, 0);
  EXPECT_LT(on, 0.004);
  EXPECT_GT(between_directions, 5 * on);
  EXPECT_GT(between_points, 5 * on);
  std::printf(
      "mean depth error: on stored rays %.4f, half a direction off %.4f, half a super "
      "pixel off %.4f\n",
      on, between_directions, between_points);
}

TEST(Odd, APlateauAtTheTopIsHitWhereTheRaysStart) {
  // A relief whose top is a plateau at depth 0 with a pit: rays from super pixels on the
  // plateau hit it at once (kOddStartDepth: a ray starting exactly on it used to slip into the
  // solid and come back from deep inside, so a brick wall drew as a flat, wrongly lit plane).
  GlContext::shared();
  std::vector<float> depths(32 * 32, 0.0f);
  for (int y = 12; y < 20; ++y)
    for (int x = 12; x < 20; ++x) depths[size_t(y) * 32 + x] = 1.0f;
  ReliefMap map = test::map_from_depths(32, 32, depths);
  const OddMap odd = build_odd_map(map, {8, 4}, true, glm::dvec2(0.2));
  for (int ka = 0; ka < 4; ++ka)
    for (int kb = 0; kb < 4; ++kb) {
      EXPECT_NEAR(odd.texels[odd.index(0, 0, ka, kb)].a, 0.0, 1e-6);  // on the plateau
      EXPECT_GT(odd.texels[odd.index(4, 4, ka, kb)].a, 0.05);         // over the pit
    }
  EXPECT_EQ(odd.missed_rays, 0);
}

TEST(Odd, FiniteFromStraightDownToLevelAndAtTheAcosEnds) {
  const SceneDesc scene = test::procedural_scene("sines", 64, 0.08, true);
  for (const View& view : {View{90, 0}, View{90, 45}, View{1, 0}, View{0, 0}})
    for (bool direction_major : {true, false})
      for (bool interpolate : {false, true}) {
        SCOPED_TRACE(std::to_string(view.elevation_deg) + " " + std::to_string(direction_major) +
                     std::to_string(interpolate));
        const test::Measured m = test::measure(
            scene, "odd",
            {{"direction_major", double(direction_major)}, {"interpolate", double(interpolate)}},
            view, 48);
        EXPECT_EQ(m.metrics.at("nonfinite_px"), 0);
        for (const auto& [column, value] : m.metrics.named())
          if (m.metrics.at("union_px") > 0) {
            EXPECT_FALSE(std::isinf(value)) << column;
          }
      }
  // Probe rays almost level along +-u and +-v: cosines at +-1 (and past it by rounding) and
  // the pole of the angles.
  OddProbe p = odd_on_sines(16, 8, true);
  std::vector<ProbeRay> rays;
  for (const glm::vec3& d : {glm::vec3(1e6f, 0, 1), glm::vec3(-1e6f, 0, 1), glm::vec3(0, 1e6f, 1),
                             glm::vec3(0, -1e6f, 1), glm::vec3(1e6f, 1e6f, 1), glm::vec3(0, 0, 1)})
    rays.push_back({glm::vec3(0.3f, 0.7f, 0.0f), d});
  for (const ProbeHit& h : p.technique->probe(p.map, *p.gpu, rays, glm::dvec2(0.3))) {
    EXPECT_TRUE(std::isfinite(h.t));
    EXPECT_TRUE(std::isfinite(h.depth));
    EXPECT_GE(h.depth, 0.0f);
    EXPECT_LE(h.depth, 1.0f);
  }
}

}  // namespace
}  // namespace rl
