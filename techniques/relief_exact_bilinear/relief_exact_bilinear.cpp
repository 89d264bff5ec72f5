// Exact bilinear traversal: Baboud & Decoret's centerline walk with an exact ray-patch solve.
#include "technique/shader_technique.h"

namespace rl {

class ReliefExactBilinear final : public Described<ReliefExactBilinear, ShaderTechnique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {
        .name = "relief_exact_bilinear",
        .title = "Exact bilinear traversal (centerline walk, exact ray-patch solve per cell)",
        .citation =
            "Beyond Baboud & Decoret 2006, Section 3.3: solves the saddle case of their "
            "Figure 3 exactly",
        .effects = {Effect::SelfShadow, Effect::DepthCorrect, Effect::AmbientOcclusion,
                    Effect::SceneShadows},
        .params = {},
        .draws = {.proxies = {Proxy::Base, Proxy::Box}},
        .contract = {.answer = Answer::Exact,
                     .max_fetches = [](const RayQuery& q) { return walk_cells(q) + 2; },
                     .max_fetches_formula = "cells walked (centerlines crossed + 1, at most "
                                            "16384; one gather each), + 2 to shade",
                     .accuracy = "the first hit on the bilinear surface, up to float rounding"}};
  }

 protected:
  std::string intersect_file() const override {
    return "techniques/relief_exact_bilinear/relief_exact_bilinear.glsl";
  }
};

RL_REGISTER_TECHNIQUE(ReliefExactBilinear);

}  // namespace rl
