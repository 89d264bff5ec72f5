// Parallax (offset) mapping, book chapter 5 Listing 5.1.
#include "technique/shader_technique.h"

namespace rl {

class ParallaxMapping final : public Described<ParallaxMapping, ShaderTechnique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {
        .name = "parallax",
        .title = "Parallax (offset) mapping",
        .citation = "Book chapter 5, 'Parallax mapping', Listing 5.1 (after Kaneko et al. 2001)",
        .effects = {Effect::DepthCorrect, Effect::AmbientOcclusion, Effect::SceneShadows},
        .params =
            {{.name = "offset_limiting",
              .kind = ParamKind::Bool,
              .default_value = 1,
              .min_value = 0,
              .max_value = 1,
              .doc =
                  "shift by d * view.xy of the unit view vector (Listing 5.1) instead of reaching "
                  "the view ray at depth d",
              .define = "RL_OFFSET_LIMITING"},
             {.name = "bias",
              .kind = ParamKind::Float,
              .default_value = 0,
              .min_value = -1,
              .max_value = 1,
              .doc =
                  "depth subtracted before shifting (Listing 5.1 uses half the scale because its "
                  "polygon sits mid-relief; ReliefLab's base is the top, so 0)",
              .define = "RL_PARALLAX_BIAS"}},
        .draws = {.reads = {Representation::Heightfield, Representation::Layers,
                            Representation::MetaRuntime}},
        .contract = {.answer = Answer::Approximation,
                     .max_fetches = [](const RayQuery&) { return 1 + 2; },
                     .max_fetches_formula = "1, + 2 to shade (1 more in a probe: the depth there)",
                     .accuracy = "exact only where the surface is flat at the fragment's depth",
                     .hits_from_inside = false}};
  }

 protected:
  std::string intersect_file() const override { return "techniques/parallax/parallax.glsl"; }
};

RL_REGISTER_TECHNIQUE(ParallaxMapping);

}  // namespace rl
