// Curvature silhouettes (book chapter 5): rays bent by the base's local quadric cut the outline
// a planar search cannot; Eq. 5.2 as printed; a flat base; hard cases (grazing views, poles,
// saddles, stretched texture coordinates) stay finite and bounded.
#include <cmath>

#include <gtest/gtest.h>

#include "gl/context.h"
#include "gl/shader_library.h"
#include "scene/base_mesh.h"
#include "scene/relief_asset.h"
#include "support/test_support.h"
#include "technique/shader_technique.h"
#include "truth/displaced_truth.h"
#include "truth/truth_render.h"

namespace rl {
namespace {

const ParamValues kRelief = {{"linear_steps", 32}, {"binary_steps", 6}};
ParamValues silhouette_params(int exact) {
  return {{"linear_steps", 32}, {"binary_steps", 6}, {"exact_distance", exact}};
}

TEST(Silhouette, BentRaysCutTheSilhouetteThePlanarSearchCannot) {
  SceneDesc scene = test::curved_scene("sphere", "sines", 64, 0.12);
  const test::Measured planar = test::measure(scene, "relief", kRelief, View{15, 30}, 128);
  scene.effects.add(Effect::Silhouette);
  for (int exact : {0, 1}) {
    const test::Measured bent =
        test::measure(scene, "relief_silhouette", silhouette_params(exact), View{15, 30}, 128);
    SCOPED_TRACE("exact_distance=" + std::to_string(exact));
    // The planar search never leaves the base polygon's outline: relief sunk into the sphere
    // shows as false coverage along the whole silhouette. Bending the rays removes most.
    EXPECT_GT(planar.metrics.at("false_pct"), 5.0);
    EXPECT_LT(bent.metrics.at("false_pct"), 0.5 * planar.metrics.at("false_pct"));
    EXPECT_LT(bent.metrics.at("missed_pct") + bent.metrics.at("false_pct"),
              planar.metrics.at("false_pct"));
    EXPECT_EQ(bent.metrics.at("nonfinite_px"), 0);
  }
}

TEST(Silhouette, Eq52AsPrintedStopsShort) {
  // The chapter's b lacks the substitution's -Uz (U points out of the surface): its root, the
  // depth along U, comes out larger, so the search stops earlier and lands short of the
  // surface. The flag selects Eq. 5.2 itself, whatever exact_distance says.
  SceneDesc scene = test::curved_scene("sphere", "sines", 64, 0.12);
  scene.effects.add(Effect::Silhouette);
  ParamValues printed = silhouette_params(1);
  printed["eq52_as_printed"] = 1;
  const test::Measured full =
      test::measure(scene, "relief_silhouette", silhouette_params(1), View{30, 30}, 96);
  const test::Measured as_printed =
      test::measure(scene, "relief_silhouette", printed, View{30, 30}, 96);
  EXPECT_EQ(as_printed.metrics.at("nonfinite_px"), 0);
  EXPECT_LT(as_printed.metrics.at("fetches_mean"), full.metrics.at("fetches_mean") - 1.0);
  EXPECT_GT(as_printed.metrics.at("artifact_pct"), full.metrics.at("artifact_pct"));
  printed["exact_distance"] = 0;
  const test::Measured implied =
      test::measure(scene, "relief_silhouette", printed, View{30, 30}, 96);
  EXPECT_EQ(implied.metrics.at("fetches_mean"), as_printed.metrics.at("fetches_mean"));
  EXPECT_EQ(implied.metrics.at("artifact_pct"), as_printed.metrics.at("artifact_pct"));
}

TEST(Silhouette, OnAFlatBaseItIsTheReliefSearch) {
  // Zero curvature: f = 0 in t_max (the stable form divides by no f), nothing is discarded.
  SceneDesc scene = test::procedural_scene("pyramids", 64, 0.08);
  const test::Measured relief = test::measure(scene, "relief", kRelief, View{30, 20}, 96);
  scene.effects.add(Effect::Silhouette);
  const test::Measured bent =
      test::measure(scene, "relief_silhouette", silhouette_params(0), View{30, 20}, 96);
  EXPECT_EQ(bent.metrics.at("missed_pct"), 0.0);
  EXPECT_EQ(bent.metrics.at("false_pct"), 0.0);
  EXPECT_LT(bent.metrics.at("pos_err_p99"), relief.metrics.at("pos_err_p99") + 0.02);
  EXPECT_LT(bent.metrics.at("artifact_pct"), relief.metrics.at("artifact_pct") + 1.0);
}

// Ray-probe hard cases for the bent search: quadrics near zero and huge, saddles, rays tangent
// to the quadric (discriminant 0), f = 0, grazing and vertical rays. Every output is finite and
// the fetch count stays within the search's fixed budget (the loops are bounded).
TEST(Silhouette, HardCasesStayFiniteAndBounded) {
  GlContext::shared();
  const SceneDesc scene = test::procedural_scene("bricks", 64, 0.08);
  const ReliefMap map = build_relief_asset(scene, 64);
  GpuRelief relief(map);
  std::vector<ProbeRay> rays;
  const float quadrics[][2] = {{0, 0},   {1e-12f, 1e-12f}, {1e6f, 1e6f}, {5, -5},
                               {-5, 5},  {-1e6f, 0},       {3, 0},       {0, 3},
                               {-2, -2}, {1e-30f, -1e-30f}};
  const glm::vec3 directions[] = {{0.3f, 0.1f, 1}, {1e-7f, 0, 1},    {0, 0, 1},
                                  {2000, 1000, 1}, {1, 1, 1e-6f},    {-0.5f, 0.5f, 1},
                                  {1e6f, 0, 1},    {0, 1e-3f, 1e-3f}};
  for (const auto& q : quadrics)
    for (const glm::vec3& d : directions)
      for (float u : {0.0f, 0.5f, 0.999f}) rays.push_back({{u, u, 0}, d, {q[0], q[1]}});
  // Tangent to the quadric: s.z^2 = 4 f, f = A s.x^2 + B s.y^2 (texture units, metric 1).
  for (float sz : {1.0f, 0.01f, 100.0f})
    rays.push_back({{0.3f, 0.2f, 0}, {1, 0, sz}, {sz * sz / 4, 7}});
  for (int exact : {0, 1}) {
    auto t =
        TechniqueRegistry::instance().create("relief_silhouette", silhouette_params(exact), "test");
    t->prepare(map);
    const std::vector<ProbeHit> hits = t->probe(map, relief, rays, glm::dvec2(1.0));
    for (size_t i = 0; i < hits.size(); ++i) {
      SCOPED_TRACE("exact=" + std::to_string(exact) + " ray " + std::to_string(i));
      ASSERT_TRUE(std::isfinite(hits[i].t) && std::isfinite(hits[i].depth) &&
                  std::isfinite(hits[i].uv.x) && std::isfinite(hits[i].uv.y));
      ASSERT_LE(hits[i].fetches, 32 + 6);
      if (hits[i].hit) {
        ASSERT_GE(hits[i].t, 0.0f);
      }
    }
  }
  // Both silhouette cases of Figure 5.25: a convex quadric that the ray leaves before depth 1
  // (a miss), and a concave one it must hit.
  auto t = TechniqueRegistry::instance().create("relief_silhouette", silhouette_params(0), "test");
  const ReliefMap deep = test::map_from_depths(2, 2, {1, 1, 1, 1});  // all at the bottom
  GpuRelief deep_gpu(deep);
  const std::vector<ProbeHit> cases =
      t->probe(deep, deep_gpu,
               {{{0.5f, 0.5f, 0}, {1, 0, 0.5f}, {1, 0}}, {{0.5f, 0.5f, 0}, {1, 0, 0.5f}, {-1, 0}}},
               glm::dvec2(1.0));
  EXPECT_FALSE(cases[0].hit) << "s.z^2 < 4f: the ray returns to the top before depth 1";
  EXPECT_TRUE(cases[1].hit) << "concave: every ray reaches depth 1";
  EXPECT_NEAR(cases[1].depth, 1.0f, 0.02f);
}

// Rendered hard cases: the sphere's poles (mapping scale collapsing to the floor), the torus's
// saddles and the teapot's stretched cylindrical uvs, from grazing and vertical views.
TEST(Silhouette, PolesSaddlesAndStretchedUvsRenderFinite) {
  for (const char* base : {"sphere", "torus", "teapot"}) {
    SceneDesc scene = test::curved_scene(base, "walls", 32, 0.1);
    scene.effects.add(Effect::Silhouette);
    for (const View& v : {View{90, 0}, View{2, 45}})
      for (int exact : {0, 1}) {
        const test::Measured m =
            test::measure(scene, "relief_silhouette", silhouette_params(exact), v, 64);
        EXPECT_EQ(m.metrics.at("nonfinite_px"), 0) << base << " el=" << v.elevation_deg;
        EXPECT_LE(m.metrics.at("fetches_max"), 32 + 6 + 2) << base;  // search + normal + colour
      }
  }
}

}  // namespace
}  // namespace rl
