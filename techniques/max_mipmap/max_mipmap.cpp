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
            .effects = {Effect::SelfShadow, Effect::DepthCorrect, Effect::AmbientOcclusion,
                        Effect::SceneShadows},
            .params = {},
            .draws = {.proxies = {Proxy::Base, Proxy::Box}},
            .contract = {
                .answer = Answer::Approximation,
                .max_fetches = [](const RayQuery& q) { return quadtree_nodes(q) + 2; },
                .max_fetches_formula = "quadtree nodes entered (2 x cells crossed + 4 per level "
                                       "+ 3), + 2 to shade",
                .accuracy = "exact where the bilinear cell is linear along the ray; elsewhere the "
                            "chord between the ray's entry and exit of the cell",
                .hits_from_inside = false}};
  }

 protected:
  std::string intersect_file() const override { return "techniques/max_mipmap/max_mipmap.glsl"; }
};

RL_REGISTER_TECHNIQUE(MaxMipmap);

}  // namespace rl
