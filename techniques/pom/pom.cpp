// Parallax occlusion mapping, Tatarchuk 2006.
#include "core/error.h"
#include "technique/shader_technique.h"

namespace rl {

class ParallaxOcclusion final : public Described<ParallaxOcclusion, ShaderTechnique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {.name = "pom",
            .title = "Parallax occlusion mapping (view-dependent linear search, interpolated hit)",
            .citation =
                "Tatarchuk 2006, 'Dynamic Parallax Occlusion Mapping with Approximate "
                "Soft Shadows', I3D 2006",
            .effects = {Effect::DepthCorrect, Effect::AmbientOcclusion, Effect::SceneShadows},
            .params = {{.name = "min_samples",
                        .kind = ParamKind::Int,
                        .default_value = 8,
                        .min_value = 2,
                        .max_value = 1024,
                        .doc = "linear search samples when the view is along the normal",
                        .define = "RL_MIN_SAMPLES"},
                       {.name = "max_samples",
                        .kind = ParamKind::Int,
                        .default_value = 32,
                        .min_value = 2,
                        .max_value = 1024,
                        .doc = "linear search samples at grazing views",
                        .define = "RL_MAX_SAMPLES"}},
            .draws = {.reads = {Representation::Heightfield, Representation::Layers,
                                Representation::MetaRuntime}},
            .contract = {
                .answer = Answer::Converging,
                .max_fetches = [](const RayQuery& q) { return 1 + q.param("max_samples") + 2; },
                .max_fetches_formula = "1 + max_samples, + 2 to shade",
                .knobs = {{"min_samples"}, {"max_samples"}},
                .finest = {{"min_samples", 1024}, {"max_samples", 1024}},
                .t_error = [](const RayQuery& q) { return 1.0 / q.param("min_samples"); },
                .accuracy = "the first crossing to within one sample step (at most 1 / "
                            "min_samples) along the ray, on surfaces with no feature thinner than "
                            "a step: the secant between the two samples around it",
                .t_resolution = [](const RayQuery& q) { return 1.0 / q.param("min_samples"); },
                .hits_from_inside = false}};
  }
  static void validate(const ParamValues& p, const std::string& where) {
    if (p.at("min_samples") > p.at("max_samples"))
      throw ConfigError(where + ": pom's min_samples must not exceed max_samples");
  }

 protected:
  std::string intersect_file() const override { return "techniques/pom/pom.glsl"; }
};

RL_REGISTER_TECHNIQUE(ParallaxOcclusion);

}  // namespace rl
