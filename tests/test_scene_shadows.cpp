// Shadows among the relief and the scene's objects (scene_shadows: Policarpo & Oliveira 2006,
// Section 7; chapter 5, "Depth Correct"): the truth's shadow of a sphere on a flat relief against
// its closed form, the shadow map's against the truth's on displaced relief (at the hits' depth
// and at the base's), the relief's shadow on an object, and that a scene without the effect
// compiles no shadow-map code, draws no shadow map and traces no shadow ray; and on a curved
// base.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "gl/context.h"
#include "gl/shader_library.h"
#include "metrics/op_cost.h"
#include "run/cells.h"
#include "run/memory_estimate.h"
#include "support/test_support.h"
#include "technique/shader_technique.h"

namespace rl {
namespace {

const ParamValues kRelief = {{"linear_steps", 64}, {"binary_steps", 8}};

// A sphere of radius `r` at height `h` over the relief, lit by a point light.
SceneDesc sphere_over(const std::string& relief, double depth, const glm::dvec3& light, double r,
                      double h) {
  SceneDesc s =
      test::procedural_scene(relief, 64, depth, false,
                             relief == "pyramids" ? std::map<std::string, double>{{"count", 6}}
                                                  : std::map<std::string, double>{});
  s.framing = Framing::Fit;
  s.light_position = light;
  SceneObject sphere;
  sphere.center = {0, 0, h};
  sphere.radius = r;
  s.objects = {sphere};
  s.effects = {Effect::DepthCorrect, Effect::SceneShadows};
  return s;
}

TEST(SceneShadows, TheTruthShadowsTheFlatReliefWhereTheWayToTheLightMeetsTheSphere) {
  // On a flat relief a point is in the sphere's shadow exactly where the segment from it to the
  // light passes within the sphere's radius of its centre.
  const glm::dvec3 light(0.8, 0.3, 2.0), centre(0, 0, 0.3);
  const double r = 0.15;
  const SceneDesc scene = sphere_over("flat", 0.08, light, r, centre.z);
  const test::Measured m = test::measure(scene, "relief", kRelief, View{60, 200}, 160);
  long inside = 0, outside = 0;
  for (size_t i = 0; i < m.truth.size(); ++i) {
    if (!m.truth.covered(i) || shows_object(m.truth, i)) continue;
    const glm::dvec3 p(m.truth.position[i]);
    const glm::dvec3 along = light - p;
    const double t = std::clamp(glm::dot(centre - p, along) / glm::dot(along, along), 0.0, 1.0);
    const double miss = glm::length(p + t * along - centre);
    // The sphere is drawn and traced as 48 x 24 flat quads: its outline lies within 0.5% of r.
    if (miss < 0.98 * r) {
      ++inside;
      EXPECT_TRUE(m.truth.shadowed(i)) << "passing " << miss << " from the centre";
    } else if (miss > 1.02 * r) {
      ++outside;
      EXPECT_FALSE(m.truth.shadowed(i)) << "passing " << miss << " from the centre";
    }
  }
  EXPECT_GT(inside, 500);
  EXPECT_GT(outside, 5000);
  // The shadow map agrees but for its texels along the edge.
  EXPECT_LT(m.metrics.at("relief_shadow_disagree_pct"), 1.0);
}

TEST(SceneShadows, OnDisplacedReliefTheShadowFollowsTheHitsOnlyAtTheirDepth) {
  // Pyramids 0.15 deep under a floating sphere, lit from aside: drawn into the shadow map and
  // looked up at the found hits, the sphere's shadow falls where the truth's does; at the base,
  // it falls where the undisplaced plane would catch it.
  SceneDesc scene = sphere_over("pyramids", 0.15, {0.6, -0.4, 1.6}, 0.14, 0.12);
  const test::Measured corrected = test::measure(scene, "relief", kRelief, View{40, 30}, 160);
  scene.shadow_map.corrected_depth = false;
  const test::Measured base = test::measure(scene, "relief", kRelief, View{40, 30}, 160);
  long shadowed = 0;
  for (size_t i = 0; i < corrected.truth.size(); ++i)
    shadowed += corrected.truth.covered(i) && !shows_object(corrected.truth, i) &&
                corrected.truth.shadowed(i);
  EXPECT_GT(shadowed, 400);
  EXPECT_LT(corrected.metrics.at("relief_shadow_disagree_pct"), 1.5);
  EXPECT_GT(base.metrics.at("relief_shadow_disagree_pct"),
            3 * corrected.metrics.at("relief_shadow_disagree_pct"));
  EXPECT_GT(corrected.truth_stats.shadow_rays, corrected.truth_stats.primary_rays);
}

TEST(SceneShadows, TheReliefShadowsAnObjectSunkIntoIt) {
  // A sphere down where four large pyramids meet, lit over the one between it and the light:
  // the pyramid shadows the lower part of the sphere's side that faces the light, which nothing
  // else can shadow.
  const glm::dvec3 light(1.84, 1.84, 1.5);
  SceneDesc scene = sphere_over("pyramids", 0.3, light, 0.1, -0.22);
  scene.relief.options["count"] = 2;
  const test::Measured m = test::measure(scene, "relief", kRelief, View{50, 45}, 320);
  long by_relief = 0, agreed = 0;
  for (size_t i = 0; i < m.truth.size(); ++i) {
    if (!m.truth.covered(i) || !shows_object(m.truth, i) || !m.truth.shadowed(i)) continue;
    const glm::dvec3 p(m.truth.position[i]), n(m.truth.normal[i]);
    if (glm::dot(n, glm::normalize(light - p)) < 0.3) continue;  // its own far side
    ++by_relief;
    agreed += m.technique.covered(i) && m.technique.shadowed(i);
  }
  EXPECT_GT(by_relief, 50);
  EXPECT_GT(agreed, 0.8 * by_relief);
  EXPECT_LT(m.metrics.at("object_shadow_disagree_pct"), 10.0);
}

TEST(SceneShadows, OnACurvedBaseTheShadowFollowsTheDisplacedSurface) {
  // Bricks on a sphere, a small sphere beside it lit from beyond: its shadow falls on the bricks
  // (the world-space truth's shadow rays from the relief and from the object), and the map at
  // the hits' depth agrees with the truth where the one at the base lights the mortar.
  SceneDesc scene = test::curved_scene("sphere", "bricks", 256, 0.04);
  scene.tile = 4;
  scene.light_position = {1.2, -0.8, 1.4};
  SceneObject ball;
  ball.center = {0.55, -0.35, 0.3};
  ball.radius = 0.12;
  scene.objects = {ball};
  scene.effects = {Effect::DepthCorrect, Effect::SceneShadows};
  const test::Measured corrected =
      test::measure(scene, "relief_exact_bilinear", {}, View{50, 330}, 160);
  scene.shadow_map.corrected_depth = false;
  const test::Measured base = test::measure(scene, "relief_exact_bilinear", {}, View{50, 330}, 160);
  long relief_shadowed = 0, object_px = 0;
  for (size_t i = 0; i < corrected.truth.size(); ++i) {
    if (!corrected.truth.covered(i)) continue;
    if (shows_object(corrected.truth, i))
      ++object_px;
    else
      relief_shadowed += corrected.truth.shadowed(i);
  }
  EXPECT_GT(object_px, 100);
  EXPECT_GT(relief_shadowed, 300);
  EXPECT_GT(corrected.truth_stats.shadow_rays, corrected.truth_stats.primary_rays);
  EXPECT_LT(corrected.metrics.at("relief_shadow_disagree_pct"), 2.0);
  EXPECT_GT(base.metrics.at("relief_shadow_disagree_pct"),
            1.5 * corrected.metrics.at("relief_shadow_disagree_pct"));
}

TEST(SceneShadows, WithoutTheEffectNoShadowMapCodeNoShadowRays) {
  GlContext::shared();
  int checked = 0;
  for (const std::string& name : TechniqueRegistry::instance().names()) {
    auto t = TechniqueRegistry::instance().create(name, {}, "test");
    auto* shader = dynamic_cast<const ShaderTechnique*>(t.get());
    if (!shader || !t->info().effects.has(Effect::SceneShadows)) continue;
    for (auto target : {RenderTarget::Kind::GBuffer, RenderTarget::Kind::ColorOnly}) {
      const GLuint plain = ShaderLibrary::shared().program(shader->surface_program({}, target));
      const GLuint with =
          ShaderLibrary::shared().program(shader->surface_program({Effect::SceneShadows}, target));
      EXPECT_EQ(glGetUniformLocation(plain, "rl_shadow_map"), -1) << name;
      EXPECT_NE(glGetUniformLocation(with, "rl_shadow_map"), -1) << name;
    }
    ++checked;
  }
  EXPECT_GE(checked, 14);  // every technique drawn by the shared surface pass
  SceneDesc scene = sphere_over("pyramids", 0.15, {0.6, -0.4, 1.6}, 0.14, 0.12);
  scene.effects = {Effect::DepthCorrect};
  const test::Measured m = test::measure(scene, "relief", kRelief, View{40, 30}, 64);
  EXPECT_EQ(m.truth_stats.shadow_rays, 0u);
  for (size_t i = 0; i < m.technique.size(); ++i) {
    ASSERT_FALSE(m.technique.shadowed(i));
    ASSERT_FALSE(m.truth.shadowed(i));
  }
  EXPECT_FALSE(m.metrics.has("relief_shadow_disagree_pct"));
}

TEST(SceneShadows, HostileLightsAndMapsStayFiniteForEveryTechnique) {
  // A light grazing the base from afar, one a thousand units off, and a 16-texel map: every
  // technique that declares the effect (one added later included) draws finite pixels with a
  // shadow flag of 0 or 1, and the truth traces its shadow rays.
  struct Hostile {
    const char* name;
    glm::dvec3 light;
    int size;
  };
  const Hostile cases[] = {{"grazing", {6.0, 0.5, 0.08}, 1024},
                           {"far", {900.0, -300.0, 900.0}, 1024},
                           {"tiny map", {0.6, -0.4, 1.6}, 16}};
  int drawn = 0;
  for (const Hostile& c : cases) {
    SceneDesc scene = sphere_over("pyramids", 0.15, c.light, 0.14, 0.12);
    scene.shadow_map.size = c.size;
    for (const std::string& name : TechniqueRegistry::instance().names()) {
      const TechniqueInfo& info = TechniqueRegistry::instance().find(name)->info;
      if (!info.effects.has(Effect::SceneShadows) || !cannot_render(info, scene).empty()) continue;
      SCOPED_TRACE(std::string(c.name) + " light, " + name);
      const test::Measured m = test::measure(scene, name, {}, View{40, 30}, 48);
      EXPECT_EQ(m.metrics.at("nonfinite_px"), 0);
      EXPECT_GT(m.truth_stats.shadow_rays, 0u);
      for (size_t i = 0; i < m.technique.size(); ++i) {
        const float flag = m.technique.normal[i].w;
        ASSERT_TRUE(flag == 0.0f || flag == 1.0f) << "pixel " << i << ": " << flag;
      }
      ++drawn;
    }
  }
  EXPECT_GE(drawn, 3 * 14);
}

TEST(SceneShadows, TheMemoryEstimateCountsTheShadowMap) {
  auto estimate = [](const std::string& shadows) {
    const std::string text = R"([sweep]
name = "t"
elevations = [45]
viewports = [16]
[[technique]]
name = "relief"
[[scene]]
name = "lit"
relief = { procedural = "sines", resolution = 64 }
light = [0.6, -0.4, 1.6]
)" + shadows;
    const SweepConfig config = parse_sweep_config(text, "t.toml", ".");
    return estimate_cell_memory(config, expand_cells(config).front());
  };
  const MemoryEstimate none = estimate("");
  const MemoryEstimate big =
      estimate("effects = [\"scene_shadows\"]\nshadow_map = { size = 8192 }\n");
  // Its depth and, while its pass is counted, its op counts: 36 bytes a texel.
  EXPECT_GE(big.bytes - none.bytes, 8192.0 * 8192.0 * 36);
  EXPECT_NE(big.what.find("shadow map"), std::string::npos) << big.what;
}

TEST(SceneShadows, AShadowMapPassAddsItsOpsPerFramePixel) {
  OpCost frame, pass;
  frame.warp_ops_per_px.fill(2.0);
  frame.counted_fragments = 100;
  pass.warp_ops_per_px.fill(3.0);
  pass.counted_fragments = 400;
  const OpCost both = with_pass(frame, pass, 4.0);  // a map of 4x the frame's pixels
  for (double v : both.warp_ops_per_px) EXPECT_DOUBLE_EQ(v, 2.0 + 3.0 * 4.0);
  EXPECT_DOUBLE_EQ(both.counted_fragments, 500);
  // A pass that shaded nothing (its counts NaN) adds nothing.
  const OpCost none = with_pass(frame, OpCost::none(), 4.0);
  for (double v : none.warp_ops_per_px) EXPECT_DOUBLE_EQ(v, 2.0);
}

TEST(SceneShadows, TheFramesModelledCostIncludesTheShadowMap) {
  const std::string dir = test::scratch_dir("scene_shadows_cost");
  const std::string sweep = R"([sweep]
name = "shadow-cost"
views = [[40, 30]]
viewports = [[64, 64]]
frames = 1
)";
  const std::string scene = R"(relief = { procedural = "pyramids", resolution = 32 }
depth = 0.15
light = [0.6, -0.4, 1.6]
objects = [{ shape = "sphere", center = [0.05, -0.05, 0.12], radius = 0.14 }]
)";
  const SweepConfig config = test::run_sweep_in(
      sweep + "[[scene]]\nname = \"plain\"\nframing = \"fit\"\n" + scene +
          "effects = [\"depth_correct\"]\n[[scene]]\nname = \"shadowed\"\n" + scene +
          "effects = [\"depth_correct\", \"scene_shadows\"]\nshadow_map = { size = 256 }\n"
          "[[technique]]\nname = \"relief\"\nlinear_steps = 16\nbinary_steps = 4\n",
      dir);
  const auto rows = test::rows_by_scene(config, dir);
  // The shadow map (256^2, 16x the frame's pixels) runs the search for every texel the relief
  // covers: its ops dwarf the frame's own.
  EXPECT_GT(rows.at("shadowed").at("warp_fetch_ops").get<double>(),
            4 * rows.at("plain").at("warp_fetch_ops").get<double>());
  EXPECT_GT(rows.at("shadowed").at("model_frame_ms").get<double>(),
            rows.at("plain").at("model_frame_ms").get<double>());
}

}  // namespace
}  // namespace rl
