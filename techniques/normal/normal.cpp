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
            .effects = {Effect::DepthCorrect, Effect::AmbientOcclusion},
            .params = {},
            .meta_relief = true};
  }

 protected:
  std::string intersect_file() const override { return "techniques/normal/normal.glsl"; }
};

RL_REGISTER_TECHNIQUE(NormalMapping);

}  // namespace rl
