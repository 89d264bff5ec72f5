// Simulate only the effects a scene asks for: no shadow code compiled, no shadow rays traced.
#include <gtest/gtest.h>

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
  EXPECT_LT(shadowed.metrics.shadow_disagree_pct, 10.0);
}

}  // namespace
}  // namespace rl
