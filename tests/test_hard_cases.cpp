// Hard cases: grazing views, views along a texel row, texture borders and tiling seams,
// one-texel walls, saddles and quantised normals. Every output stays finite, every loop
// bounded, and errors show up in the metrics rather than being hidden.
#include <cmath>

#include <gtest/gtest.h>

#include "gl/context.h"
#include "gpu/gpu_scene.h"
#include "relief/heightfield_reference.h"
#include "relief/procedural.h"
#include "support/test_support.h"

namespace rl {
namespace {

using test::measure;
using test::procedural_scene;

// Most fetches a technique may take per pixel (search + normal + colour).
double fetch_bound(const std::string& technique, const ParamValues& p) {
  if (technique == "relief") return p.at("linear_steps") - 1 + p.at("binary_steps") + 2;
  if (technique == "parallax") return 3;
  return 2;
}

void expect_stable(const test::Measured& m, const std::string& technique, const ParamValues& p) {
  EXPECT_EQ(m.metrics.at("nonfinite_px"), 0);
  EXPECT_LE(m.metrics.at("fetches_max"), fetch_bound(technique, p));
  for (const auto& [name, value] : m.metrics.named()) EXPECT_TRUE(std::isfinite(value)) << name;
}

TEST(HardCases, GrazingViewAtOneDegree) {
  const ParamValues relief = {{"linear_steps", 8}, {"binary_steps", 5}};
  for (const char* kind : {"bricks", "walls", "pyramids"}) {
    // A long base seen from close by at one degree: most rays meet it between 1 and 10
    // degrees (a small quad at 1 degree would be a line of pixels).
    SceneDesc scene = procedural_scene(kind, 64, 0.08, true);
    scene.size = 8;
    scene.tile = 8;
    scene.distance = 1.5;
    SCOPED_TRACE(kind);
    test::Measured r = measure(scene, "relief", relief, View{1, 30}, 128);
    expect_stable(r, "relief", relief);
    EXPECT_EQ(r.truth_stats.unresolved, 0);  // every truth ray found the surface
    EXPECT_GT(r.metrics.at("covered_px"), 128 * 128 / 4);
    // At one degree a coarse search cannot be right: its error must be reported.
    EXPECT_GT(r.metrics.at("artifact_pct"), 1.0);
    for (const char* t : {"normal", "parallax"}) {
      ParamValues none;
      expect_stable(measure(scene, t, none, View{1, 30}, 128), t, none);
    }
  }
}

TEST(HardCases, ViewExactlyAlongATexelRow) {
  // Azimuth 0: the centre column's rays have a v component of exactly 0; the top-down view
  // (90 degrees) has rays with both lateral components near 0.
  SceneDesc scene = procedural_scene("bricks", 64, 0.08, true);
  const ParamValues p = {{"linear_steps", 32}, {"binary_steps", 6}};
  for (View v : {View{30, 0}, View{30, 90}, View{90, 0}}) {
    test::Measured m = measure(scene, "relief", p, v, 65);
    expect_stable(m, "relief", p);
  }
  // The same in ray-probe mode, against the reference, with direction components of exactly 0.
  // Rays start a hair above the top: one starting exactly on a plateau's edge touches the
  // surface at t = 0 (a hit for the reference) while a search first looks one step in.
  ReliefMap map = make_procedural("bricks", 64, {}, 10.0, "test");
  GpuRelief relief(map);
  auto t = TechniqueRegistry::instance().create(
      "relief", {{"linear_steps", 256}, {"binary_steps", 8}}, "test");
  std::vector<ProbeRay> rays;
  for (int i = 0; i < 64; ++i) {
    const float u = (i + 0.5f) / 64.0f;  // exactly on texel centres: bilinear weights of 0
    rays.push_back({glm::vec3(u, 0.5f / 64.0f, -1e-4f), glm::vec3(0.7f, 0.0f, 1.0f)});
    rays.push_back({glm::vec3(0.5f / 64.0f, u, -1e-4f), glm::vec3(0.0f, -0.7f, 1.0f)});
    rays.push_back({glm::vec3(u, u, -1e-4f), glm::vec3(0.0f, 0.0f, 1.0f)});
  }
  std::vector<ProbeHit> hits = t->probe(map, relief, rays, glm::dvec2(0.08));
  for (size_t i = 0; i < rays.size(); ++i) {
    ReferenceHit ref =
        intersect_heightfield(map, glm::dvec3(rays[i].origin), glm::dvec3(rays[i].direction), 1.0);
    ASSERT_TRUE(std::isfinite(hits[i].t));
    EXPECT_NEAR(hits[i].t, ref.t, 1.0 / 256 + 2e-3) << "ray " << i;
  }
}

TEST(HardCases, TextureBordersAndTilingSeams) {
  // Rays starting exactly on u, v = 0 and 1 and on tile seams, crossing them both ways.
  ReliefMap map = make_procedural("pyramids", 32, {{"count", 2}}, 10.0, "test");
  GpuRelief relief(map);
  auto t = TechniqueRegistry::instance().create(
      "relief", {{"linear_steps", 128}, {"binary_steps", 8}}, "test");
  std::vector<ProbeRay> rays;
  for (float u : {0.0f, 1.0f, -1.0f, 2.0f, 1e-7f, 1.0f - 1e-7f})
    for (float su : {-0.5f, 0.5f, 0.0f})
      rays.push_back({glm::vec3(u, 0.37f, -1e-4f), glm::vec3(su, 0.05f, 1.0f)});
  std::vector<ProbeHit> hits = t->probe(map, relief, rays, glm::dvec2(0.08));
  for (size_t i = 0; i < rays.size(); ++i) {
    ReferenceHit ref =
        intersect_heightfield(map, glm::dvec3(rays[i].origin), glm::dvec3(rays[i].direction), 1.0);
    EXPECT_NEAR(hits[i].t, ref.t, 1.0 / 128 + 2e-3) << "ray " << i;
  }
  // A tiled scene: seams run through the view; the relief stays as accurate as untiled.
  SceneDesc tiled = procedural_scene("sines", 32, 0.08, true);
  tiled.tile = 3;
  const ParamValues p = {{"linear_steps", 64}, {"binary_steps", 6}};
  test::Measured m = measure(tiled, "relief", p, View{35, 20}, 128);
  expect_stable(m, "relief", p);
  EXPECT_LT(m.metrics.at("artifact_pct"), 1.0);
}

TEST(HardCases, OneTexelWallsAreJumpedByCoarseSearchesAndReported) {
  SceneDesc scene = procedural_scene("walls", 64, 0.08, true, {{"spacing", 8}});
  const ParamValues coarse = {{"linear_steps", 4}, {"binary_steps", 4}};
  const ParamValues fine = {{"linear_steps", 256}, {"binary_steps", 6}};
  test::Measured c = measure(scene, "relief", coarse, View{25, 20}, 96);
  test::Measured f = measure(scene, "relief", fine, View{25, 20}, 96);
  expect_stable(c, "relief", coarse);
  expect_stable(f, "relief", fine);
  EXPECT_GT(c.metrics.at("artifact_pct"), 3 * f.metrics.at("artifact_pct"));
  EXPECT_GT(c.metrics.at("pos_err_p99"), 0.1);  // jumped walls put hits far behind them
}

TEST(HardCases, ZeroLengthQuantisedNormalsStayFinite) {
  // A texel encoding the zero vector (mid-grey after 8-bit quantisation) must not produce NaN.
  SceneDesc scene = procedural_scene("sines", 16, 0.08, true);
  test::Measured ok = measure(scene, "relief", {}, View{45, 30}, 48);
  EXPECT_EQ(ok.metrics.at("nonfinite_px"), 0);
  // Build the same map with every normal zeroed and check the shader and truth fallbacks.
  ReliefMap map = make_procedural("sines", 16, {}, 10.0, "test");
  for (auto& t : map.relief) t = glm::vec4(0.5f, 0.5f, 0.5f, t.a);
  quantize_8bit(map);
  EXPECT_EQ(decode_normal(glm::dvec4(0.5, 0.5, 0.5, 0)), glm::dvec3(0, 0, 1));
  GpuRelief relief(map);
  GpuBase base(make_base_geometry(scene));
  const Camera cam = make_camera(scene, View{45, 30}, 48, 48);
  auto t = TechniqueRegistry::instance().create("relief", {}, "test");
  RenderTarget target(48, 48, RenderTarget::Kind::GBuffer);
  target.bind_and_clear();
  t->render(FrameInput{scene, map, relief, base, cam, EffectSet{}}, RenderTarget::Kind::GBuffer);
  GBuffer g;
  target.read_back(g);
  for (size_t i = 0; i < g.size(); ++i)
    if (g.covered(i)) {
      ASSERT_TRUE(std::isfinite(g.normal[i].x) && std::isfinite(g.color[i].r));
    }
}

}  // namespace
}  // namespace rl
