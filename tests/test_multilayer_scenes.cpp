// Non-height-field relief in scenes, against the geometry it stands for: the weave on a
// plane (multilayer and a heightfield compared; double depth in techniques/double_depth/), with
// an object sitting in it, on closed curved bases (the far side through the gaps, two passes,
// silhouettes, the teapot whose uvs overlap), relief impostors seen from every side, and every
// registered technique on the weave. The layer bake: tests/test_layer_bake.cpp; the search itself:
// techniques/multilayer/test_multilayer.cpp.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "core/triangle_mesh.h"
#include "relief/pattern_mesh.h"
#include "scene/base_mesh.h"
#include "scene/relief_asset.h"
#include "support/test_support.h"
#include "truth/pattern_base_truth.h"

namespace rl {
namespace {

SceneDesc impostor_scene(const std::string& mesh_file, int layers) {
  SceneDesc s;
  s.name = "impostor";
  s.relief.mesh_path = std::string(RELIEFLAB_SOURCE_DIR) + "/assets/meshes/" + mesh_file;
  s.relief.layers = layers;
  s.relief.native = {128, 128};
  s.truth = TruthLevel::Mesh;
  s.empty_floor = true;
  const BakeFrame frame = relief_bake_frame(s.relief, load_mesh(s.relief.mesh_path));
  s.depth = s.size * frame.height / frame.side;  // as read_scene_files() sets it
  s.distance = 1.6;
  return s;
}

// The weave (128^2, 4 layers) tiled twice on a 32-segment sphere, 0.06 deep.
SceneDesc weave_on_a_sphere() {
  SceneDesc scene = test::weave_scene(128, TruthLevel::Mesh);
  scene.base.kind = "sphere";
  scene.base.segments = 32;
  scene.tile = 2;
  scene.depth = 0.06;
  return scene;
}

TEST(MultilayerScenes, BeatsTheHeightfieldOnTheWeaveAgainstTheMesh) {
  const SceneDesc scene = test::weave_scene(128, TruthLevel::Mesh);
  for (double el : {60.0, 30.0}) {
    SCOPED_TRACE(el);
    const test::Measured ml = test::measure(scene, "multilayer", {}, View{el, 30}, 128);
    const test::Measured hf =
        test::measure(scene, "relief", {{"linear_steps", 32}}, View{el, 30}, 128);
    EXPECT_GT(ml.metrics.at("covered_px"), 2000);  // a fitted camera: the quad in view
    EXPECT_EQ(ml.metrics.at("nonfinite_px"), 0);
    // The heightfield extrudes every thread down to the floor; the layers keep the gaps.
    EXPECT_LT(ml.metrics.at("wrong_pct"), 0.6 * hf.metrics.at("wrong_pct"));
    EXPECT_LT(ml.metrics.at("false_pct"), 0.6 * hf.metrics.at("false_pct"));
    std::printf(
        "weave %2.0f deg: multilayer wrong %.2f%% (false %.2f%%), relief wrong %.2f%% "
        "(false %.2f%%)\n",
        el, ml.metrics.at("wrong_pct"), ml.metrics.at("false_pct"), hf.metrics.at("wrong_pct"),
        hf.metrics.at("false_pct"));
  }
}

TEST(Impostor, ShadowsFromALightBelowTheQuad) {
  // An impostor is lit from either side: its light rays are searched from the light's side of
  // the depth range, and the truth's run toward the light until they leave it.
  SceneDesc scene = impostor_scene("bunny.obj", 8);
  scene.effects.add(Effect::SelfShadow);
  scene.light_position = {0.6, -0.4, -1.2};
  for (const View& view : {View{60, 30}, View{-40, 210}}) {
    SCOPED_TRACE(view.elevation_deg);
    const test::Measured m = test::measure(scene, "multilayer", {{"linear_steps", 64}}, view, 128);
    std::printf("bunny impostor lit from below, %+3.0f deg: shadows disagree on %.2f%%\n",
                view.elevation_deg, m.metrics.at("shadow_disagree_pct"));
    EXPECT_GT(m.truth_stats.shadow_rays, 0u);
    EXPECT_LT(m.metrics.at("shadow_disagree_pct"), 6.0);
  }
}

TEST(MultilayerScenes, DepthCorrectionLetsAnObjectSitInTheWeave) {
  // A plain sphere pushed halfway into the weave: with depth_correct the threads in front of
  // it hide it and it hides the threads behind it, per pixel, as in the truth.
  SceneDesc scene = test::weave_scene(128, TruthLevel::Mesh);
  scene.objects.push_back({"sphere", {0.05, -0.05, -0.075}, 0.14, {0.2, 0.8, 0.3}});
  const ParamValues p = {{"linear_steps", 64}};
  const test::Measured plain = test::measure(scene, "multilayer", p, View{35, 30}, 128);
  scene.effects.add(Effect::DepthCorrect);
  const test::Measured corrected = test::measure(scene, "multilayer", p, View{35, 30}, 128);
  std::printf("weave + sphere: object disagreement without %.3f%%, with %.3f%%\n",
              plain.metrics.at("object_disagree_pct"), corrected.metrics.at("object_disagree_pct"));
  EXPECT_GT(plain.metrics.at("object_disagree_pct"),
            5 * corrected.metrics.at("object_disagree_pct"));
  EXPECT_LT(corrected.metrics.at("object_disagree_pct"), 1.0);
}

TEST(MultilayerScenes, TheWeaveOnASphereShowsItsFarSideThroughTheGaps) {
  // Figure 1 / Section 5: on a closed base the far side shows through the pattern's gaps,
  // searched upward from inside. One pass (all faces) and two passes (front, then back faces)
  // draw the same image; a one-sided heightfield search misses the far side.
  SceneDesc scene = weave_on_a_sphere();
  const View view{30, 30};
  const test::Measured one = test::measure(scene, "multilayer", {{"linear_steps", 32}}, view, 96);
  const test::Measured two =
      test::measure(scene, "multilayer", {{"linear_steps", 32}, {"two_pass", 1}}, view, 96);
  const test::Measured hf = test::measure(scene, "relief", {{"linear_steps", 32}}, view, 96);
  std::printf(
      "weave on a sphere: missed multilayer %.2f%% (false %.2f%%), relief %.2f%% (false "
      "%.2f%%)\n",
      one.metrics.at("missed_pct"), one.metrics.at("false_pct"), hf.metrics.at("missed_pct"),
      hf.metrics.at("false_pct"));
  EXPECT_EQ(one.metrics.at("nonfinite_px"), 0);
  EXPECT_EQ(one.technique.color, two.technique.color);
  EXPECT_LT(one.metrics.at("missed_pct"), 2.0);
  EXPECT_GT(hf.metrics.at("missed_pct"), 2 * one.metrics.at("missed_pct"));
  // Chapter 5 silhouettes on the front faces: the bent rays put fewer hits off the pattern.
  scene.effects.add(Effect::Silhouette);
  const test::Measured bent = test::measure(scene, "multilayer", {{"linear_steps", 32}}, view, 96);
  std::printf("weave on a sphere: wrong %.2f%% planar, %.2f%% with silhouettes\n",
              one.metrics.at("wrong_pct"), bent.metrics.at("wrong_pct"));
  EXPECT_EQ(bent.metrics.at("nonfinite_px"), 0);
  EXPECT_LT(bent.metrics.at("wrong_pct"), one.metrics.at("wrong_pct") - 3.0);
}

TEST(PatternBaseTruth, TheWeaveMappedOntoASphereStaysInItsShell) {
  // Every pattern point mapped onto the sphere (radius 0.5) lies between the base and one
  // relief depth below it; rays through the centre of the view hit it.
  const BaseMesh sphere =
      make_base_mesh(BaseDesc{.kind = "sphere", .path = "", .segments = 24}, 1.0, 2.0);
  const PatternBaseTruth truth(make_pattern_mesh("weave", {}, "test"), sphere, 0.06);
  ASSERT_GT(truth.triangles(), 10000u);
  const DisplacedHit h = truth.intersect({0, 0, 3}, {0, 0, -1}, 10.0);
  ASSERT_TRUE(h.hit);
  // The flat 24-segment base lies inside the unit sphere by at most 1 - cos(pi / 24) radii.
  const double r = glm::length(h.position);
  EXPECT_LE(r, 0.5 + 1e-6);
  EXPECT_GE(r, 0.5 * std::cos(3.14159265 / 24) - 0.06 - 1e-6);
  EXPECT_TRUE(h.has_surface);
}

TEST(PatternBaseTruth, ASolidFloorStopsTheRaysThatMissThePattern) {
  // Policarpo & Oliveira 2006, Figure 9 (right): under the pattern lies the underlying model.
  // Rays at the sphere's middle either meet the same pattern point as without the floor, or
  // stop on the floor: one relief depth inside the base, before the open sphere's next hit,
  // facing out along the base's normal, in the floor's colour.
  const BaseMesh sphere =
      make_base_mesh(BaseDesc{.kind = "sphere", .path = "", .segments = 24}, 1.0, 2.0);
  const TriangleMesh weave = make_pattern_mesh("weave", {}, "test");
  const glm::vec3 green(0.0f, 1.0f, 0.0f);
  const double depth = 0.06;
  const PatternBaseTruth open(weave, sphere, depth), floored(weave, sphere, depth, green);
  int floor_hits = 0, rays = 0;
  for (int j = -20; j <= 20; ++j)
    for (int i = -20; i <= 20; ++i, ++rays) {
      // Off the mesh's planes of symmetry, where rays would run along base edges.
      const glm::dvec3 eye(0.3 * (i + 0.37) / 20.0, 0.3 * (j + 0.21) / 20.0, 3.0), dir(0, 0, -1);
      const DisplacedHit a = open.intersect(eye, dir, 10.0), b = floored.intersect(eye, dir, 10.0);
      ASSERT_TRUE(b.hit);
      if (b.albedo != glm::dvec3(green)) {
        EXPECT_NEAR(b.t, a.t, 1e-5);  // the pattern in front of the floor, untouched
        continue;
      }
      ++floor_hits;
      EXPECT_TRUE(!a.hit || a.t > b.t);
      const double r = glm::length(b.position);
      EXPECT_LE(r, 0.5 - depth + 1e-6);
      // A flat facet of the sphere of radius 0.5 - depth (24 segments) sags by at most cos^2.
      EXPECT_GE(r, (0.5 - depth) * std::pow(std::cos(3.14159265 / 24), 2) - 1e-6);
      EXPECT_EQ(b.surface_normal, b.normal);  // shaded with the base's normal, facing the eye
      EXPECT_GT(glm::dot(b.normal, b.position / r), 0.99);
    }
  std::printf("solid floor under the weave on a sphere: %d of %d rays end on the floor\n",
              floor_hits, rays);
  EXPECT_GT(floor_hits, rays / 10);
  EXPECT_LT(floor_hits, rays);
}

TEST(MultilayerScenes, TheMissingPatternDrawnAsTheUnderlyingModel) {
  // Figure 9 (right): a pattern on a sphere over a solid floor. Every pixel of the truth's
  // sphere is drawn (the floor shows through every gap), and the search's parallax beats
  // normal mapping's none. With silhouettes the rays that leave through the top are dropped.
  SceneDesc scene = weave_on_a_sphere();
  scene.empty_floor = false;
  const View view{30, 30};
  const test::Measured ml = test::measure(scene, "multilayer", {{"linear_steps", 32}}, view, 96);
  const test::Measured flat = test::measure(scene, "normal", {}, view, 96);
  scene.effects.add(Effect::Silhouette);
  const test::Measured bent = test::measure(scene, "multilayer", {{"linear_steps", 32}}, view, 96);
  std::printf(
      "weave on a sphere over a solid floor: multilayer wrong %.2f%% (PSNR %.1f dB, false "
      "%.2f%%), with silhouettes false %.2f%%, normal mapping %.2f%% (%.1f dB)\n",
      ml.metrics.at("wrong_pct"), ml.metrics.at("psnr_db"), ml.metrics.at("false_pct"),
      bent.metrics.at("false_pct"), flat.metrics.at("wrong_pct"), flat.metrics.at("psnr_db"));
  for (const test::Measured* m : {&ml, &flat, &bent}) EXPECT_EQ(m->metrics.at("nonfinite_px"), 0);
  EXPECT_LT(ml.metrics.at("missed_pct"), 0.5);
  EXPECT_LT(bent.metrics.at("missed_pct"), 2.0);  // bent rays that leave the floor's outline early
  EXPECT_LT(ml.metrics.at("wrong_pct"), flat.metrics.at("wrong_pct") - 10.0);
  EXPECT_GT(ml.metrics.at("psnr_db"), flat.metrics.at("psnr_db") + 1.0);
  EXPECT_LT(bent.metrics.at("false_pct"), 0.5 * ml.metrics.at("false_pct"));
}

TEST(MultilayerScenes, TheWeaveOnTheTeapotWhoseUvsOverlap) {
  // The teapot's cylindrical uvs cover some uvs twice (spout and handle over the body): the
  // truth maps the pattern onto every triangle anyway, and the technique's error stays finite.
  SceneDesc scene = test::weave_scene(128, TruthLevel::Mesh);
  scene.base.kind = "teapot";
  scene.tile = 2;
  scene.depth = 0.06;
  const test::Measured m =
      test::measure(scene, "multilayer", {{"linear_steps", 32}, {"two_pass", 1}}, View{30, 30}, 96);
  EXPECT_GT(m.metrics.at("covered_px"), 500);
  EXPECT_EQ(m.metrics.at("nonfinite_px"), 0);
  EXPECT_LT(m.metrics.at("missed_pct"), 10.0);
}

TEST(MultilayerScenes, TheWeaveOverASolidFloor) {
  // floor = "solid": the gaps show the floor at depth 1 (facing up, kLayeredFloorColor) in
  // the technique and the truth alike; nothing is counted as an unresolved truth ray.
  SceneDesc scene = test::weave_scene(128, TruthLevel::Mesh);
  scene.empty_floor = false;
  const test::Measured ml =
      test::measure(scene, "multilayer", {{"linear_steps", 32}}, View{25, 30}, 128);
  const test::Measured hf =
      test::measure(scene, "relief", {{"linear_steps", 32}}, View{25, 30}, 128);
  std::printf(
      "weave over a solid floor, 25 deg: wrong multilayer %.2f%% (PSNR %.1f dB), relief "
      "%.2f%% (%.1f dB)\n",
      ml.metrics.at("wrong_pct"), ml.metrics.at("psnr_db"), hf.metrics.at("wrong_pct"),
      hf.metrics.at("psnr_db"));
  EXPECT_EQ(ml.truth_stats.unresolved, 0);
  EXPECT_EQ(ml.metrics.at("missed_pct") + ml.metrics.at("false_pct"),
            0.0);  // the floor fills every pixel
  EXPECT_LT(ml.metrics.at("wrong_pct"), 5.0);
  EXPECT_GT(ml.metrics.at("psnr_db"),
            hf.metrics.at("psnr_db") + 3.0);  // the floor's colour is shaded alike
  EXPECT_LT(ml.metrics.at("wrong_pct"), 0.3 * hf.metrics.at("wrong_pct"));
}

TEST(MultilayerScenes, EveryTechniqueDrawsTheWeaveFinitely) {
  // A non-height-field scene is one more hard case for every registered technique: the
  // heightfield ones see its top layer. Outputs finite, whatever their error.
  const SceneDesc scene = test::weave_scene(64, TruthLevel::Mesh);
  for (const std::string& name : TechniqueRegistry::instance().names()) {
    const TechniqueInfo& info = TechniqueRegistry::instance().find(name)->info;
    if (!cannot_render(info, scene).empty()) continue;
    SCOPED_TRACE(name);
    const test::Measured m = test::measure(scene, name, {}, View{20, 30}, 64);
    EXPECT_EQ(m.metrics.at("nonfinite_px"), 0);
    for (const auto& [column, value] : m.metrics.named())
      EXPECT_TRUE(std::isfinite(value)) << column;
  }
}

TEST(Impostor, TheBunnyFromBothSidesAndGrazingAgainstTheMesh) {
  // Section 4: one quad through the middle of the object shows it from any side. Against the
  // bunny mesh itself (representation error included): 128 steps, 128^2, 4 layers. Rays that
  // leave the quad's footprint must find nothing: sampled with GL_REPEAT they met the bunny's
  // other side and drew tens of percent of false pixels at 20 and -30 degrees.
  const SceneDesc scene = impostor_scene("bunny.obj", 4);
  for (const View& view : {View{60, 30}, View{20, 120}, View{-30, 210}, View{-70, 300}}) {
    SCOPED_TRACE(view.elevation_deg);
    const test::Measured m = test::measure(scene, "multilayer", {{"linear_steps", 128}}, view, 128);
    EXPECT_GT(m.metrics.at("covered_px"), 800);
    EXPECT_EQ(m.metrics.at("nonfinite_px"), 0);
    EXPECT_LE(m.metrics.at("missed_pct") + m.metrics.at("false_pct"), 2.0);
    EXPECT_LE(m.metrics.at("wrong_pct"), 12.0);
    std::printf("bunny impostor %+3.0f deg: wrong %.2f%% (missed %.2f%%, false %.2f%%)\n",
                view.elevation_deg, m.metrics.at("wrong_pct"), m.metrics.at("missed_pct"),
                m.metrics.at("false_pct"));
  }
}

}  // namespace
}  // namespace rl
