// The Embree truth: its tessellation tolerance, agreement with the exact reference across
// tile seams, and shadow rays traced only when asked for.
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "core/parallel.h"
#include "core/sharded_counter.h"
#include "relief/heightfield_reference.h"
#include "relief/procedural.h"
#include "scene/relief_asset.h"
#include "support/test_support.h"
#include "truth/heightfield_truth.h"

namespace rl {
namespace {

// Stated tolerance: every truth hit lies within the tessellation bound (vertically) of the
// bilinear surface the shaders sample, plus float rounding of the stored vertices.
TEST(Truth, EveryHitLiesWithinTheStatedBoundOfTheBilinearSurface) {
  for (const char* kind : {"sines", "bricks", "pyramids", "walls"}) {
    ReliefMap m = make_procedural(kind, 64, {}, 10.0, "test");
    HeightfieldTruth truth(m, 2e-3);
    EXPECT_LE(truth.tessellation_bound(), 2e-3 + 1e-12) << kind;
    int hits = 0;
    for (const test::TangentRay& r :
         test::random_tangent_rays(3000, 10, 85, 0.08 * 64 / 64.0, 11, -1e-6)) {
      // Rays end a hair below depth 1, as the renderer's do: the walls' floor lies exactly at 1.
      TruthHit h = truth.intersect(r.origin, r.direction, 0, 1.0 + 1e-4);
      if (!h.hit) continue;
      ++hits;
      const double surface = m.sample_depth(h.point.x, h.point.y);
      ASSERT_LE(std::abs(h.point.z - surface), truth.tessellation_bound() + 2e-6)
          << kind << " at uv " << h.point.x << ", " << h.point.y;
    }
    EXPECT_GT(hits, 2900) << kind;
  }
}

// Doubling the tessellation moves no truth hit by more than the stated tolerance, measured
// in depth units of the hit, except where the ray grazes a ridge and changes which side it
// hits: those are counted and must stay rare.
TEST(Truth, DoublingTheTessellationMovesHitsWithinTolerance) {
  const double tolerance = 2e-3;
  for (const char* kind : {"sines", "pyramids", "bricks"}) {
    ReliefMap m = make_procedural(kind, 64, {}, 10.0, "test");
    HeightfieldTruth coarse(m, tolerance);
    HeightfieldTruth fine(m, tolerance, 1u << 24, 2 * coarse.subdivision());
    int moved = 0, total = 0;
    double worst = 0;
    for (const test::TangentRay& r : test::random_tangent_rays(4000, 20, 85, 0.08, 5, -1e-6)) {
      TruthHit a = coarse.intersect(r.origin, r.direction, 0, 1.0 + 1e-6);
      TruthHit b = fine.intersect(r.origin, r.direction, 0, 1.0 + 1e-6);
      ASSERT_TRUE(a.hit && b.hit);
      ++total;
      const double dz = std::abs(a.point.z - b.point.z);
      if (dz > tolerance)
        ++moved;
      else
        worst = std::max(worst, dz);
    }
    EXPECT_LE(moved, total / 1000)
        << kind << ": " << moved << " of " << total << " hits moved more than " << tolerance;
    EXPECT_LE(worst, tolerance) << kind;
  }
}

TEST(Truth, AgreesWithTheExactReferenceAcrossTileSeams) {
  // Grazing rays (5-20 degrees) travel across several tiles; the reference wraps by texture
  // repetition, the truth by walking tiles: they must find the same surface.
  ReliefMap m = make_procedural("sines", 32, {}, 10.0, "test");
  HeightfieldTruth truth(m, 5e-4);
  std::vector<double> err;
  for (const test::TangentRay& r : test::random_tangent_rays(2000, 5, 85, 0.5, 3, -1e-6)) {
    TruthHit h = truth.intersect(r.origin, r.direction, 0, 1.0 + 1e-6);
    ReferenceHit ref = intersect_heightfield(m, r.origin, r.direction, 1.0 + 1e-6);
    ASSERT_TRUE(h.hit && ref.hit);
    err.push_back(std::abs(h.point.z - ref.depth));
  }
  std::sort(err.begin(), err.end());
  EXPECT_LE(err[err.size() * 999 / 1000], 5e-3);  // 99.9% within a few bounds along grazing rays
  EXPECT_LE(err[err.size() / 2], 5e-4);
}

TEST(Truth, TracesShadowRaysOnlyWhenAsked) {
  SceneDesc scene = test::procedural_scene("bricks", 64);
  ReliefMap m = build_relief_asset(scene, 64);
  HeightfieldTruth truth(m);
  const Camera cam = make_camera(scene, View{45, 30}, 48, 48);
  TruthStats without, with;
  GBuffer a = render_truth(truth, m, scene, cam, EffectSet{}, &without);
  GBuffer b = render_truth(truth, m, scene, cam, EffectSet{Effect::SelfShadow}, &with);
  EXPECT_EQ(without.unresolved, 0);
  EXPECT_EQ(with.unresolved, 0);
  EXPECT_EQ(without.shadow_rays, 0u);
  EXPECT_GT(without.primary_rays, 0u);
  EXPECT_EQ(with.shadow_rays, with.primary_rays);
  long shadowed = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_FALSE(a.shadowed(i));
    shadowed += b.shadowed(i);
  }
  EXPECT_GT(shadowed, 0);  // bricks cast shadows into the mortar
}

TEST(Truth, FlatMapHitsTheBaseExactly) {
  SceneDesc scene = test::procedural_scene("flat", 16);
  ReliefMap m = build_relief_asset(scene, 16);
  HeightfieldTruth truth(m);
  const Camera cam = make_camera(scene, View{37, 12}, 40, 40);
  GBuffer g = render_truth(truth, m, scene, cam, EffectSet{});
  long covered = 0;
  for (size_t i = 0; i < g.size(); ++i) {
    if (!g.covered(i)) continue;
    ++covered;
    EXPECT_NEAR(g.position[i].z, 0.0, 1e-6);
  }
  EXPECT_GT(covered, 400);
}

}  // namespace
}  // namespace rl

namespace rl {
namespace {

// Occlusion queries (shadow and AO rays) start on the surface, where a tessellated truth and
// the surface differ most: from hits on the bricks (steep one-texel walls) and the pyramids,
// rays up into the hemisphere must be blocked exactly when the reference walk (texel cells
// only, no Embree) finds the surface before they leave the relief at the top.
TEST(Truth, OcclusionFromTheSurfaceAgreesWithTheReferenceWalk) {
  for (const char* kind : {"bricks", "pyramids"}) {
    SceneDesc scene = test::procedural_scene(kind, 256, 0.08, true);
    const ReliefMap m = build_relief_asset(scene, 256);
    HeightfieldTruth truth(m);
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u01(0, 1);
    long rays = 0, differ = 0, blocked = 0;
    for (const test::TangentRay& r : test::random_tangent_rays(400, 20, 80, 0.08, 3, -1e-6)) {
      const TruthHit h = truth.intersect(r.origin, r.direction, 0, 1.0 + 1e-4);
      if (!h.hit) continue;
      for (int k = 0; k < 16; ++k) {
        // A direction in the upper hemisphere of the base, in texture units (depth 0.08).
        const double a = 6.2831853 * u01(rng), c = std::sqrt(u01(rng)), s = std::sqrt(1 - c * c);
        const glm::dvec3 l(s * std::cos(a), s * std::sin(a), -c / 0.08);
        const double t0 = 1e-4 / std::max(1.0, glm::length(l)), t_exit = -h.point.z / l.z;
        if (!(t_exit > t0)) continue;
        const glm::dvec3 start = h.point + l * t0;
        const ReferenceHit ref = intersect_heightfield(m, start, l, t_exit - t0);
        const bool occluded = truth.occluded(h.point, l, t0, t_exit);
        ++rays;
        blocked += occluded;
        differ += occluded != ref.hit;
      }
    }
    EXPECT_GT(rays, 800) << kind;  // rays from the bricks' flat tops leave at once: not counted
    EXPECT_GT(blocked, rays / 20) << kind;
    EXPECT_EQ(differ, 0) << kind << ": " << differ << " of " << rays;
  }
}

// The ray counters count every ray traced on every core: a sharded count summed on read, as
// one atomic was (it cost the AO truth nearly half its time), and the truth's own counts.
TEST(Truth, RayCountsHoldUnderEveryCore) {
  ShardedCounter count;
  parallel_for(
      100000,
      [&](size_t b, size_t e) {
        for (size_t i = b; i < e; ++i) ++count;
      },
      7);
  EXPECT_EQ(count.load(), 100000u);
  count += 5;
  EXPECT_EQ(count.load(), 100005u);
  SceneDesc scene = test::procedural_scene("pyramids", 64, 0.08, true);
  const HeightfieldTruth truth(build_relief_asset(scene, 64));
  parallel_for(
      5000,
      [&](size_t b, size_t e) {
        for (size_t i = b; i < e; ++i)
          truth.occluded(glm::dvec3(double(i % 64) / 64, 0.3, 0.5), glm::dvec3(0.2, 0.1, -1), 1e-4,
                         0.5);
      },
      16);
  EXPECT_EQ(truth.shadow_rays(), 5000u);
  EXPECT_EQ(truth.primary_rays(), 0u);
}

}  // namespace
}  // namespace rl
