// Interval mapping, a technique built outside ReliefLab's tree against its installed package
// (README.md here says how). It is registered, documented, swept and held to its contract like
// a built-in one.
#include "technique/shader_technique.h"

namespace rl_example {

using namespace rl;

class IntervalMapping final : public Described<IntervalMapping, ShaderTechnique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {
        .name = "interval_mapping",
        .title = "Interval mapping (linear search + regula falsi)",
        .citation =
            "Risser, Shah & Pattanaik 2005, 'Interval Mapping', University of Central "
            "Florida technical report (I3D 2005 poster)",
        .effects = {Effect::SelfShadow, Effect::DepthCorrect, Effect::AmbientOcclusion},
        // Each parameter declared once, its shader define with it (the linear steps as every
        // linear search declares them: technique/contract.h).
        .params = {linear_steps_param(16, "linear search steps through the depth range"),
                   {.name = "secant_steps",
                    .kind = ParamKind::Int,
                    .default_value = 3,
                    .min_value = 0,
                    .max_value = 32,
                    .doc = "regula falsi refinements of the bracket the linear search found",
                    .define = "RL_SECANT_STEPS"}},
        .draws = {.reads = {Representation::Heightfield, Representation::Layers,
                            Representation::MetaRuntime}},
        .contract = {.answer = Answer::Converging,
                     .max_fetches =
                         [](const RayQuery& q) {
                           return 1 + q.param("linear_steps") + q.param("secant_steps") + 2;
                         },
                     .max_fetches_formula = "1 + linear_steps + secant_steps, + 2 to shade",
                     .knobs = {{"linear_steps"}, {"secant_steps"}},
                     .finest = {{"linear_steps", 1024}, {"secant_steps", 32}},
                     // Regula falsi keeps a bracket around the crossing but need not shrink it (one
                     // end can stay put): the answer is promised within one linear step.
                     .t_error = one_linear_step,
                     .accuracy = "the first crossing to within one linear step along the ray, on "
                                 "surfaces with no feature thinner than a step",
                     .t_resolution = one_linear_step,
                     .hits_from_inside = false}};
  }

 protected:
  // The key relieflab_add_plugin() embedded the file under: plugins/<target>/<path>.
  std::string intersect_file() const override {
    return "plugins/relieflab_interval_mapping/interval_mapping.glsl";
  }
};

RL_REGISTER_TECHNIQUE(IntervalMapping);

}  // namespace rl_example
