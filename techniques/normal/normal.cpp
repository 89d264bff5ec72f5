// Normal mapping: the baseline every relief technique is compared with.
#include "technique/shader_technique.h"

namespace rl {

class NormalMapping final : public Described<NormalMapping, ShaderTechnique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {.name = "normal",
            .title = "Normal mapping",
            .citation =
                "Book chapter 5, 'Parallax mapping' and Figure 5.9 (the normal-map baseline); "
                "Chapter 3 bump mapping",
            .effects = {Effect::DepthCorrect, Effect::AmbientOcclusion, Effect::SceneShadows},
            .params = {},
            .draws = {.reads = {Representation::Heightfield, Representation::Layers,
                                Representation::MetaRuntime}},
            .contract = {.answer = Answer::ShadingOnly,
                         .max_fetches = [](const RayQuery&) { return 2; },
                         .max_fetches_formula = "2, to shade",
                         .hits_from_inside = false}};
  }

 protected:
  std::string intersect_file() const override { return "techniques/normal/normal.glsl"; }
};

RL_REGISTER_TECHNIQUE(NormalMapping);

}  // namespace rl
