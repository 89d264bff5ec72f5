// Ray-probe mode: each technique's own GLSL intersection on tangent-space rays, compared with
// the double-precision reference (relief) or the technique's closed form (parallax, normal).
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "gl/context.h"
#include "gpu/gpu_scene.h"
#include "relief/heightfield_reference.h"
#include "relief/procedural.h"
#include "support/test_support.h"
#include "technique/technique.h"

namespace rl {
namespace {

using test::probe;

TEST(RayProbe, ReliefMatchesTheReferenceWithinItsSearchInterval) {
  // Smooth bumps, float texels: with 64 linear steps no feature is thinner than a step along
  // these rays, so the search finds the reference's crossing to within its binary interval.
  ReliefMap map = make_procedural("sines", 64, {{"frequency", 2}}, 10.0, "test");
  const int linear = 64, binary = 8;
  std::vector<ProbeRay> rays =
      test::as_probe_rays(test::random_tangent_rays(4096, 30, 85, 0.08, 21, 0.0));
  std::vector<ProbeHit> hits =
      probe("relief", {{"linear_steps", linear}, {"binary_steps", binary}}, map, rays);
  const double interval = 1.0 / linear / std::pow(2.0, binary);
  // GL_LINEAR's filtering weights are not exact in every implementation (llvmpipe rounds
  // them to 8 bits): allow that much depth on the steepest slope of this map.
  const double filtering = 2e-3;
  int worst_i = -1;
  double worst = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    ReferenceHit ref =
        intersect_heightfield(map, glm::dvec3(rays[i].origin), glm::dvec3(rays[i].direction), 1.0);
    ASSERT_TRUE(ref.hit);
    ASSERT_TRUE(std::isfinite(hits[i].t));
    const double err = std::abs(hits[i].t - ref.t);
    if (err > worst) worst = err, worst_i = int(i);
    EXPECT_LE(hits[i].fetches, linear - 1 + binary);
  }
  EXPECT_LE(worst, interval + filtering) << "worst ray " << worst_i;
}

TEST(RayProbe, ReliefFetchCountFollowsTheListing) {
  ReliefMap map = make_procedural("constant", 16, {{"value", 0.3}}, 1.0, "test");
  std::vector<ProbeRay> rays = {{glm::vec3(0.5f, 0.5f, 0.0f), glm::vec3(0.2f, 0.1f, 1.0f)}};
  // 10 linear steps: depths 0.1, 0.2, 0.3 (inside) -> 3 fetches, then 5 binary.
  ProbeHit h = probe("relief", {{"linear_steps", 10}, {"binary_steps", 5}}, map, rays)[0];
  EXPECT_EQ(h.fetches, 3 + 5);
  EXPECT_NEAR(h.depth, 0.3, 0.1 / 32 + 1e-6);
}

TEST(RayProbe, ParallaxIsItsClosedForm) {
  ReliefMap map = make_procedural("sines", 32, {}, 10.0, "test");
  std::vector<ProbeRay> rays =
      test::as_probe_rays(test::random_tangent_rays(512, 10, 80, 0.08, 4, 0.0));
  // Square texture units, and a map whose v unit is 4x longer in world than its u unit (a
  // 4:1 strip): the unit view vector's z must come from each axis's own world length.
  for (const glm::dvec2 aspect : {glm::dvec2(0.08), glm::dvec2(0.08, 0.02)}) {
    for (double limiting : {0.0, 1.0}) {
      std::vector<ProbeHit> hits =
          probe("parallax", {{"offset_limiting", limiting}}, map, rays, aspect);
      for (size_t i = 0; i < rays.size(); ++i) {
        const glm::dvec3 o(rays[i].origin), s(rays[i].direction);
        const double d = map.sample_depth(o.x, o.y);
        double scale = d;
        if (limiting != 0) {
          const glm::dvec2 world = glm::dvec2(s) / aspect;
          scale *= 1.0 / std::sqrt(1.0 + glm::dot(world, world));
        }
        SCOPED_TRACE("limiting " + std::to_string(limiting) + " aspect v " +
                     std::to_string(aspect.y));
        EXPECT_NEAR(hits[i].uv.x, o.x + s.x * scale, 2e-3);
        EXPECT_NEAR(hits[i].uv.y, o.y + s.y * scale, 2e-3);
        EXPECT_EQ(hits[i].fetches, 2);
      }
    }
  }
}

TEST(RayProbe, NormalMappingReturnsTheEntryPoint) {
  ReliefMap map = make_procedural("bricks", 32, {}, 10.0, "test");
  std::vector<ProbeRay> rays =
      test::as_probe_rays(test::random_tangent_rays(64, 10, 80, 0.08, 9, 0.0));
  std::vector<ProbeHit> hits = probe("normal", {}, map, rays);
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_FLOAT_EQ(hits[i].uv.x, rays[i].origin.x);
    EXPECT_FLOAT_EQ(hits[i].depth, 0.0f);
    EXPECT_EQ(hits[i].fetches, 0);
  }
}

}  // namespace
}  // namespace rl
