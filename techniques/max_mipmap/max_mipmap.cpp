// Maximum mipmaps, Tevs, Ihrke & Seidel 2008.
#include "technique/quadtree_technique.h"

namespace rl {

class MaxMipmap final : public Described<MaxMipmap, QuadtreeTechnique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {.name = "max_mipmap",
            .title = "Maximum mipmaps (quadtree ray stepping, linear profile per cell)",
            .citation =
                "Tevs, Ihrke & Seidel 2008, 'Maximum Mipmaps for Fast, Accurate, and Scalable "
                "Dynamic Height Field Rendering', I3D 2008",
            .effects = {Effect::SelfShadow, Effect::DepthCorrect, Effect::AmbientOcclusion},
            .params = {},
            .box_proxy = true};
  }

 protected:
  std::string intersect_file() const override { return "techniques/max_mipmap/max_mipmap.glsl"; }
};

RL_REGISTER_TECHNIQUE(MaxMipmap);

}  // namespace rl
