// Hierarchical exact search: min-depth quadtree skipping, exact ray-patch solve per cell.
#include "technique/quadtree_technique.h"

namespace rl {

class ReliefHierarchicalExact final : public Described<ReliefHierarchicalExact, QuadtreeTechnique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {
        .name = "relief_hierarchical_exact",
        .title = "Hierarchical exact search (min-depth quadtree, exact ray-patch solve per cell)",
        .citation =
            "Beyond the published work: Tevs, Ihrke & Seidel 2008's maximum-mipmap traversal "
            "over the bilinear cells, with relief_exact_bilinear's exact solve at level 0",
        .effects = {Effect::SelfShadow, Effect::DepthCorrect, Effect::AmbientOcclusion},
        .params = {},
        .box_proxy = true,
        .contract = {.answer = Answer::Exact,
                     .max_fetches = [](const RayQuery& q) { return quadtree_nodes(q) + 2; },
                     .max_fetches_formula = "quadtree nodes entered (2 x cells crossed + 4 per "
                                            "level + 3), + 2 to shade",
                     .accuracy = "the first hit on the bilinear surface, up to float rounding"}};
  }

 protected:
  std::string intersect_file() const override {
    return "techniques/relief_hierarchical_exact/relief_hierarchical_exact.glsl";
  }
};

RL_REGISTER_TECHNIQUE(ReliefHierarchicalExact);

}  // namespace rl
