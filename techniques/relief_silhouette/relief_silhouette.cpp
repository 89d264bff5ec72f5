// Relief mapping with curvature silhouettes, book chapter 5 Listings 5.5-5.7.
#include <cmath>
#include "technique/shader_technique.h"

namespace rl {

class ReliefSilhouette final : public Described<ReliefSilhouette, ShaderTechnique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {
        .name = "relief_silhouette",
        .title =
            "Relief mapping with curvature silhouettes (bent rays through a per-vertex quadric)",
        .citation =
            "Book chapter 5, 'Silhouette edges and Relief Texture mapping', Listings 5.5-5.7, "
            "Equations 5.1-5.3 (Oliveira & Policarpo 2005)",
        .effects = {Effect::Silhouette, Effect::SelfShadow, Effect::DepthCorrect,
                    Effect::AmbientOcclusion, Effect::SceneShadows},
        .params =
            {linear_steps_param(10, "linear search samples over [0, t_max] (Listing 5.6: 10)"),
             binary_steps_param(
                 6, "binary search refinements after the linear search (Listing 5.6: 6)"),
             {.name = "exact_distance",
              .kind = ParamKind::Bool,
              .default_value = 0,
              .min_value = 0,
              .max_value = 1,
              .doc = "1: ray-quadric distance of Equation 5.2 with the discriminant test; 0: the "
                     "vertical distance of Equation 5.3 (the chapter's 'twofold speedup')"},
             {.name = "eq52_as_printed",
              .kind = ParamKind::Bool,
              .default_value = 0,
              .min_value = 0,
              .max_value = 1,
              .doc = "1: Equation 5.2 (whatever exact_distance says) with its linear "
                     "coefficient as the chapter prints it, b = 2 A Px Ux + 2 B Py Uy, without the "
                     "-Uz that substituting R = P + U s into Equation 5.1 gives",
              .define = "RL_EQ52_AS_PRINTED"},
             {.name = "plane_t_max",
              .kind = ParamKind::Bool,
              .default_value = 0,
              .min_value = 0,
              .max_value = 1,
              .doc = "1: the samples spread over the tangent plane's [0, 1 / s_z] (depth 1 on a "
                     "flat base); 0: over Listing 5.7's t_max, the nearer of where the bent ray "
                     "reaches depth 1 and where it returns to depth 0 (Figure 5.25's cases)",
              .neutral_default = true,
              .define = "RL_PLANE_T_MAX"}},
        .draws = {.reads = {Representation::Heightfield, Representation::Layers,
                            Representation::MetaRuntime}},
        .contract = {.answer = Answer::Converging,
                     .max_fetches = linear_binary_fetches_shaded,
                     .max_fetches_formula = "linear_steps + binary_steps, + 2 to shade",
                     .knobs = linear_binary_knobs(),
                     .finest = linear_binary_finest(),
                     .t_error = linear_binary_t_error,
                     .accuracy =
                         "on a planar base, the first crossing to within one linear step / "
                         "2^binary_steps along the ray, on surfaces with no feature thinner than "
                         "a linear step",
                     .t_resolution = one_linear_step}};
  }

 protected:
  std::string intersect_file() const override {
    return "techniques/relief_silhouette/relief_silhouette.glsl";
  }
  // Eq. 5.2 as printed is a form of the exact quadric distance: either sets RL_QUADRIC_EXACT.
  Defines parameter_defines() const override {
    return {{"RL_QUADRIC_EXACT", exact_distance_ ? "1" : "0"}};
  }

 private:
  const bool exact_distance_ = param<bool>("exact_distance") || param<bool>("eq52_as_printed");
};

RL_REGISTER_TECHNIQUE(ReliefSilhouette);

}  // namespace rl
