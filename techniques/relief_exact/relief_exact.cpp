// Exact texel traversal, Baboud & Decoret 2006 Section 3.3.
#include "technique/shader_technique.h"

namespace rl {

class ReliefExact final : public Described<ReliefExact, ShaderTechnique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {.name = "relief_exact",
            .title = "Exact texel traversal (centerline to centerline)",
            .citation =
                "Baboud & Decoret 2006, Section 3.3 'Rasterization-based intersection' "
                "(2D Amanatides & Woo 1987)",
            .effects = {Effect::SelfShadow, Effect::DepthCorrect, Effect::AmbientOcclusion},
            .params = {},
            .box_proxy = true};
  }

 protected:
  std::string intersect_file() const override {
    return "techniques/relief_exact/relief_exact.glsl";
  }
};

RL_REGISTER_TECHNIQUE(ReliefExact);

}  // namespace rl
