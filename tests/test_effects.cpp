// Simulate only the effects a scene asks for: no shadow code compiled, no shadow rays traced.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "gl/context.h"
#include "gl/shader_library.h"
#include "support/test_support.h"
#include "technique/shader_technique.h"

namespace rl {
namespace {

const ShaderTechnique& as_shader(const Technique& t) {
  return dynamic_cast<const ShaderTechnique&>(t);
}

TEST(Effects, NoShadowCodeWithoutSelfShadow) {
  GlContext::shared();
  auto relief = TechniqueRegistry::instance().create("relief", {}, "test");
  for (auto target : {RenderTarget::Kind::GBuffer, RenderTarget::Kind::ColorOnly}) {
    ProgramDesc plain = as_shader(*relief).surface_program(EffectSet{}, target);
    ProgramDesc shadowed =
        as_shader(*relief).surface_program(EffectSet{Effect::SelfShadow}, target);
    EXPECT_EQ(plain.defines.count("RL_SELF_SHADOW"), 0u);
    EXPECT_EQ(shadowed.defines.count("RL_SELF_SHADOW"), 1u);
    // What was actually compiled: the shadow block is compiled out without the define.
    const std::string& src = ShaderLibrary::shared().fragment_source(plain);
    EXPECT_EQ(src.find("#define RL_SELF_SHADOW"), std::string::npos);
    EXPECT_NE(ShaderLibrary::shared().fragment_source(shadowed).find("#define RL_SELF_SHADOW 1"),
              std::string::npos);
  }
}

TEST(Effects, ShadowRaysAndShadowedPixelsOnlyWhenAsked) {
  SceneDesc scene = test::procedural_scene("bricks", 64, 0.08, true);
  const ParamValues p = {{"linear_steps", 32}, {"binary_steps", 6}};
  test::Measured plain = test::measure(scene, "relief", p, View{40, 30}, 64);
  EXPECT_EQ(plain.truth_stats.shadow_rays, 0u);
  for (size_t i = 0; i < plain.technique.size(); ++i) ASSERT_FALSE(plain.technique.shadowed(i));

  scene.effects.add(Effect::SelfShadow);
  test::Measured shadowed = test::measure(scene, "relief", p, View{40, 30}, 64);
  EXPECT_EQ(shadowed.truth_stats.shadow_rays, shadowed.truth_stats.primary_rays);
  long tech_shadow = 0, truth_shadow = 0;
  for (size_t i = 0; i < shadowed.technique.size(); ++i) {
    tech_shadow += shadowed.technique.shadowed(i);
    truth_shadow += shadowed.truth.shadowed(i);
  }
  EXPECT_GT(tech_shadow, 0);
  EXPECT_GT(truth_shadow, 0);
  // The technique's shadows agree with the truth's on most pixels; the rest is measured.
  EXPECT_LT(shadowed.metrics.at("shadow_disagree_pct"), 10.0);
}

// --- Mip-mapped depths and normals (relief's mipmap, chapter 5) ---

double mean_tilt_deg(const GBuffer& g) {
  double sum = 0;
  long n = 0;
  for (size_t i = 0; i < g.size(); ++i)
    if (g.covered(i)) {
      sum += std::acos(std::clamp(double(glm::normalize(glm::vec3(g.normal[i])).z), -1.0, 1.0));
      ++n;
    }
  return n ? glm::degrees(sum / double(n)) : 0.0;
}

TEST(Mipmap, NoMipCodeUnlessAsked) {
  GlContext::shared();
  auto plain = TechniqueRegistry::instance().create("relief", {}, "test");
  auto mip = TechniqueRegistry::instance().create("relief", {{"mipmap", 1}}, "test");
  const ProgramDesc a = as_shader(*plain).surface_program(EffectSet{}, RenderTarget::Kind::GBuffer);
  const ProgramDesc b = as_shader(*mip).surface_program(EffectSet{}, RenderTarget::Kind::GBuffer);
  // What is compiled: the mip-mapped reads (and their texture unit) only with the define.
  EXPECT_EQ(ShaderLibrary::shared().fragment_source(a).find("#define RL_MIPMAP"),
            std::string::npos);
  EXPECT_NE(ShaderLibrary::shared().fragment_source(b).find("#define RL_MIPMAP 1"),
            std::string::npos);
}

TEST(Mipmap, LevelZeroWhereATexelCoversSeveralPixels) {
  // 32 texels across 128 pixels: the footprint is under a texel, so trilinear reads level 0
  // through the magnification filter, the same bilinear surface as without mip-mapping.
  const SceneDesc scene = test::procedural_scene("sines", 32, 0.08);
  const ParamValues plain = {{"linear_steps", 32}, {"binary_steps", 6}, {"mipmap", 0}};
  ParamValues mip = plain;
  mip["mipmap"] = 1;
  const test::Measured a = test::measure(scene, "relief", plain, View{70, 30}, 128);
  const test::Measured b = test::measure(scene, "relief", mip, View{70, 30}, 128);
  ASSERT_GT(a.metrics.at("covered_px"), 5000);
  EXPECT_EQ(a.technique.position, b.technique.position);
  EXPECT_EQ(a.technique.normal, b.technique.normal);
}

TEST(Mipmap, CoarseLevelsWherePixelsCoverManyTexels) {
  // The sines repeated 16 times, 64 texels each, over 48 pixels: about 21 texels a pixel. The
  // mip chain averages the bumps away, so its normals lean far less than the surface's; a flat
  // map is the same at every level, so mip-mapping leaves it exactly as it was.
  SceneDesc scene = test::procedural_scene("sines", 64, 0.08 / 16);
  scene.tile = 16;
  const ParamValues plain = {{"linear_steps", 32}, {"binary_steps", 6}, {"mipmap", 0}};
  ParamValues mip = plain;
  mip["mipmap"] = 1;
  const double level0 =
      mean_tilt_deg(test::measure(scene, "relief", plain, View{60, 30}, 48).technique);
  const double averaged =
      mean_tilt_deg(test::measure(scene, "relief", mip, View{60, 30}, 48).technique);
  EXPECT_GT(level0, 10.0);
  EXPECT_LT(averaged, 0.25 * level0);

  SceneDesc flat = test::procedural_scene("constant", 64, 0.08 / 16, false, {{"value", 0.4}});
  flat.tile = 16;
  const test::Measured fa = test::measure(flat, "relief", plain, View{60, 30}, 48);
  const test::Measured fb = test::measure(flat, "relief", mip, View{60, 30}, 48);
  ASSERT_GT(fa.metrics.at("covered_px"), 500);
  EXPECT_EQ(fa.technique.position, fb.technique.position);
  EXPECT_EQ(fa.technique.normal, fb.technique.normal);
}

}  // namespace
}  // namespace rl
