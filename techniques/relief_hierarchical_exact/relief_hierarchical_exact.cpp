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
        .effects = {Effect::SelfShadow, Effect::DepthCorrect, Effect::AmbientOcclusion,
                    Effect::SceneShadows},
        // Defaults: the fastest setting in GPU time by the H200's cost model
        // (results/exact-at-guess-cost); the packed blocks save fetches and cost more time.
        .params = {{.name = "start_level",
                    .kind = ParamKind::Int,
                    .default_value = 5,
                    .min_value = 0,
                    .max_value = 16,
                    .doc = "coarsest quadtree level the search starts at (at most the level whose "
                           "nodes span the ray's lateral travel; lower starts near the entry and "
                           "climbs; 16: always that level, as before)",
                    .define = "RL_START_LEVEL"},
                   {.name = "block_cells",
                    .kind = ParamKind::Int,
                    .default_value = 0,
                    .min_value = 0,
                    .max_value = 1,
                    .doc = "1: on 8-bit maps a level-1 node's four cells are read in one fetch "
                           "(their 3 x 3 corner depths packed in one RGBA32UI texel) instead of "
                           "one gather per cell",
                    .define = "RL_BLOCK_CELLS",
                    .define_when_set = true},
                   {.name = "byte_bounds",
                    .kind = ParamKind::Int,
                    .default_value = 0,
                    .min_value = 0,
                    .max_value = 1,
                    .doc = "1: on 8-bit maps node bounds are read 4 x 4 nodes at a time, 8 bits "
                           "each, with their parents' bounds derived from them: one fetch serves "
                           "two levels of the descent",
                    .define = "RL_BYTE_BOUNDS",
                    .define_when_set = true}},
        .draws = {.proxies = {Proxy::Base, Proxy::Box}},
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
  bool uses_blocks() const override { return uses_blocks_; }

 private:
  // Int switches (0 or 1), as their rows have always stored them.
  const bool uses_blocks_ = param<int>("block_cells") != 0 || param<int>("byte_bounds") != 0;
};

RL_REGISTER_TECHNIQUE(ReliefHierarchicalExact);

}  // namespace rl
