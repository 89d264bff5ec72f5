// The double-precision reference intersector, checked against analytic answers and brute force.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "support/test_support.h"

#include "relief/heightfield_reference.h"
#include "relief/procedural.h"

namespace rl {
namespace {

ReliefMap from_depths(int w, int h, const std::vector<float>& d) {
  return test::map_from_depths(w, h, d);
}

// f(t) = ray depth - surface depth; brute force checks that the reference's t is the first
// root: f < 0 everywhere before it (to the sampling step), f ~ 0 at it.
void expect_first_crossing(const ReliefMap& m, glm::dvec3 o, glm::dvec3 d, const ReferenceHit& h) {
  ASSERT_TRUE(h.hit);
  auto f = [&](double t) { return o.z + d.z * t - m.sample_depth(o.x + d.x * t, o.y + d.y * t); };
  EXPECT_NEAR(f(h.t), 0.0, 1e-9) << "t = " << h.t;
  for (double t = 0; t < h.t - 1e-6; t += 1e-4)
    ASSERT_LT(f(t), 1e-12) << "earlier crossing at t = " << t;
}

TEST(Reference, ConstantDepthIsHitAtThatDepth) {
  ReliefMap m = make_procedural("constant", 8, {{"value", 0.375}}, 1.0, "test");
  ReferenceHit h = intersect_heightfield(m, {0.3, 0.6, 0.0}, {0.7, -0.2, 1.0}, 1.0);
  ASSERT_TRUE(h.hit);
  EXPECT_DOUBLE_EQ(h.t, 0.375);
  EXPECT_NEAR(h.uv.x, 0.3 + 0.7 * 0.375, 1e-15);
}

TEST(Reference, LinearRampIsAnExactPlane) {
  // depth = x / 8 on texel centres: bilinear reconstruction is the plane itself between
  // the first and last centres (away from the wrap-around cell).
  std::vector<float> d;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) d.push_back(float(x) / 8.0f);
  ReliefMap m = from_depths(8, 8, d);
  // Surface: depth(u) = (8u - 0.5) / 8 = u - 1/16. Ray: u = 0.2 + 0.1 t, depth = t.
  // t = 0.2 + 0.1 t - 1/16  =>  t = (0.2 - 0.0625) / 0.9.
  ReferenceHit h = intersect_heightfield(m, {0.2, 0.5, 0.0}, {0.1, 0.0, 1.0}, 1.0);
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.t, (0.2 - 0.0625) / 0.9, 1e-12);
}

TEST(Reference, SaddleIsNotMissed) {
  // A 2x2 checker: every cell is a saddle (twist C = 2). A ray crossing near the saddle
  // point dips below the surface only briefly; sampling at a coarse step can miss it.
  ReliefMap m = from_depths(2, 2, {0.0f, 1.0f, 1.0f, 0.0f});
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1), a(-3, 3);
  for (int i = 0; i < 300; ++i) {
    glm::dvec3 o(u(rng), u(rng), 0.0), d(a(rng), a(rng), 1.0);
    ReferenceHit h = intersect_heightfield(m, o, d, 1.0);
    expect_first_crossing(m, o, d, h);
  }
}

TEST(Reference, RandomRaysOnSinesMatchBruteForce) {
  ReliefMap m = make_procedural("sines", 32, {}, 1.0, "test");
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-2, 2), a(-4, 4);
  for (int i = 0; i < 200; ++i) {
    glm::dvec3 o(u(rng), u(rng), 0.0), d(a(rng), a(rng), 1.0);
    expect_first_crossing(m, o, d, intersect_heightfield(m, o, d, 1.0));
  }
}

TEST(Reference, AxisAlignedAndVerticalRaysTerminate) {
  ReliefMap m = make_procedural("bricks", 32, {}, 1.0, "test");
  for (glm::dvec3 d : {glm::dvec3(0, 0, 1), glm::dvec3(3, 0, 1), glm::dvec3(0, -3, 1)}) {
    ReferenceHit h = intersect_heightfield(m, {0.5 / 32, 0.5 / 32, 0.0}, d, 1.0);
    ASSERT_TRUE(h.hit);
    EXPECT_TRUE(std::isfinite(h.t));
    EXPECT_LE(h.cells, long(std::abs(d.x) * 32 + std::abs(d.y) * 32) + 4);
  }
  // An ascending ray from above the surface never hits (one starting on it, at depth 0 on a
  // brick top, is already "at or below" it: t = 0).
  EXPECT_FALSE(intersect_heightfield(m, {0.3, 0.3, -0.1}, {0.5, 0.5, -1.0}, 1.0).hit);
  EXPECT_EQ(intersect_heightfield(m, {0.3, 0.3, 0.0}, {0.5, 0.5, -1.0}, 1.0).t, 0.0);
}

}  // namespace
}  // namespace rl
