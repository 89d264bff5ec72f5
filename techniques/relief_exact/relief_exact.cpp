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
            .effects = {Effect::SelfShadow, Effect::DepthCorrect, Effect::AmbientOcclusion,
                        Effect::SceneShadows},
            .params = {},
            .draws = {.proxies = {Proxy::Base, Proxy::Box}},
            .contract = {
                .answer = Answer::Approximation,
                .max_fetches = [](const RayQuery& q) { return 1 + walk_cells(q) + 2; },
                .max_fetches_formula = "1 + cells walked (centerlines crossed + 1, at most "
                                       "16384), + 2 to shade",
                .accuracy = "exact where the bilinear patch is linear along the ray (no twist); "
                            "elsewhere the chord between two centerline samples",
                .hits_from_inside = false}};
  }

 protected:
  std::string intersect_file() const override {
    return "techniques/relief_exact/relief_exact.glsl";
  }
};

RL_REGISTER_TECHNIQUE(ReliefExact);

}  // namespace rl
