// Parallax (offset) mapping, book chapter 5 Listing 5.1.
#include "technique/shader_technique.h"

namespace rl {

class ParallaxMapping final : public Described<ParallaxMapping, ShaderTechnique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {"parallax",
            "Parallax (offset) mapping",
            "Book chapter 5, 'Parallax mapping', Listing 5.1 (after Kaneko et al. 2001)",
            {Effect::DepthCorrect},
            {{"offset_limiting", ParamKind::Bool, 1, 0, 1,
              "shift by d * view.xy of the unit view vector (Listing 5.1) instead of reaching "
              "the view ray at depth d"},
             {"bias", ParamKind::Float, 0, -1, 1,
              "depth subtracted before shifting (Listing 5.1 uses half the scale because its "
              "polygon sits mid-relief; ReliefLab's base is the top, so 0)"}}};
  }

 protected:
  std::string intersect_file() const override { return "techniques/parallax/parallax.glsl"; }
  Defines parameter_defines() const override {
    return {{"RL_OFFSET_LIMITING", param("offset_limiting") != 0 ? "1" : "0"},
            {"RL_PARALLAX_BIAS", "(" + std::to_string(param("bias")) + ")"}};
  }
};

RL_REGISTER_TECHNIQUE(ParallaxMapping);

}  // namespace rl
