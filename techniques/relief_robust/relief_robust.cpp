// Robust binary search with precomputed safety radii, Baboud & Decoret 2006 Sections 3.4-3.5.
#include <algorithm>
#include <cmath>
#include "safety_radius.h"
#include "technique/shader_technique.h"

namespace rl {

class ReliefRobust final : public Described<ReliefRobust, ShaderTechnique> {
 public:
  using Described::Described;
  ~ReliefRobust() override {
    if (texture_) glDeleteTextures(1, &texture_);
  }
  static TechniqueInfo describe() {
    return {
        .name = "relief_robust",
        .title = "Robust binary search with safety radii",
        .citation =
            "Baboud & Decoret 2006, Sections 3.4-3.5 (safety radius, robust binary search, "
            "Figures 5-8, 12)",
        .effects = {Effect::SelfShadow, Effect::DepthCorrect, Effect::AmbientOcclusion,
                    Effect::SceneShadows},
        .params =
            {{.name = "binary_steps",
              .kind = ParamKind::Int,
              .default_value = 8,
              .min_value = 1,
              .max_value = 32,
              .doc = "binary search steps once the ray is below",
              .define = "RL_BINARY_STEPS"},
             {.name = "exact_zero_radius",
              .kind = ParamKind::Bool,
              .default_value = 0,
              .min_value = 0,
              .max_value = 1,
              .doc = "solve zero-radius columns exactly instead of clamping the radius to 1",
              .define = "RL_EXACT_ZERO_RADIUS",
              .define_when_set = true},
             {.name = "error_allowed",
              .kind = ParamKind::Float,
              .default_value = 0,
              .min_value = 0,
              .max_value = 1,
              .doc = "depth a ray may dip into a feature unseen: larger radii, faster, silhouette "
                     "errors up to this depth (Figure 12)"},
             {.name = "directions",
              .kind = ParamKind::Int,
              .default_value = 16,
              .min_value = 4,
              .max_value = 256,
              .doc = "ray azimuths sampled by the precompute"},
             {.name = "max_radius",
              .kind = ParamKind::Int,
              .default_value = 0,
              .min_value = 0,
              .max_value = 255,
              .doc =
                  "largest radius stored, texels; 0 = follow the texture (min(255, larger side))"},
             {.name = "ignore_blocked",
              .kind = ParamKind::Bool,
              .default_value = 1,
              .min_value = 0,
              .max_value = 1,
              .doc = "Section 3.5 as written: rays blocked before the texel are ignored; 0 = "
                     "conservative "
                     "radii that also hold for blocked rays"},
             {.name = "max_over_directions",
              .kind = ParamKind::Bool,
              .default_value = 0,
              .min_value = 0,
              .max_value = 1,
              .doc = "Section 3.5's words: keep the largest radius over the sampled directions "
                     "(safe for one direction only); 0 = the smallest, safe for all"}},
        .draws = {.proxies = {Proxy::Base, Proxy::Box}},
        .contract = {.answer = Answer::Converging,
                     .max_fetches =
                         [](const RayQuery& q) {
                           const double major = std::max(q.span_texels.x, q.span_texels.y);
                           const double minor = std::min(q.span_texels.x, q.span_texels.y);
                           const double lines = std::min(kWalkCellCap, std::floor(major) + 2);
                           // A zero radius walks its line's cells exactly: one gather per cell.
                           const double per_line =
                               1 + (q.param("exact_zero_radius") != 0
                                        ? std::max(1.0, std::ceil(minor / std::max(major, 1.0)) + 3)
                                        : 1.0);
                           return lines * per_line + q.param("binary_steps") + 3;
                         },
                     .max_fetches_formula =
                         "(texel lines crossed + 2) x (a radius and a depth, or with "
                         "exact_zero_radius the cells of a line), + binary_steps, + 1 "
                         "where the ray enters below depth 0 (a box side), + 2 to shade",
                     .knobs = {{"binary_steps"},
                               {"directions"},
                               {"exact_zero_radius"},
                               {"error_allowed", /*larger_is_finer=*/false},
                               {"ignore_blocked", /*larger_is_finer=*/false},
                               {"max_over_directions", /*larger_is_finer=*/false}},
                     .finest = {{"binary_steps", 32},
                                {"directions", 64},
                                {"exact_zero_radius", 1},
                                {"error_allowed", 0},
                                {"ignore_blocked", 0},
                                {"max_over_directions", 0}},
                     .accuracy =
                         "the crossing in a step of at most one safety radius (255 texels), to "
                         "within that step / 2^(binary_steps + 1): safe radii hold one crossing "
                         "per step",
                     .hits_from_inside = false},
        .columns = {{"zero_radius_pct", "%",
                     "texels whose safety radius is 0 (Figure 7: not concave there; the search "
                     "steps 1 there, or walks the line's cells with exact_zero_radius)"}}};
  }

  void prepare(const ReliefMap& map) override {
    radii_ = cached_safety_radii(map, options_);
    if (texture_) glDeleteTextures(1, &texture_);
    glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
    glTextureStorage2D(texture_, 1, GL_R8UI, radii_.width, radii_.height);
    // Integer textures are incomplete (texelFetch reads 0) under any filter but NEAREST.
    glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(texture_, 0, 0, 0, radii_.width, radii_.height, GL_RED_INTEGER,
                        GL_UNSIGNED_BYTE, radii_.radius.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  }
  size_t memory_bytes() const override { return radii_.radius.size(); }
  std::vector<std::pair<std::string, double>> frame_columns() const override {
    return {{"zero_radius_pct",
             100.0 * radii_.zero_count() / double(std::max<size_t>(radii_.radius.size(), 1))}};
  }
  bool prepared_from_cache() const override { return radii_.from_cache; }
  const SafetyRadii& radii() const { return radii_; }

 protected:
  std::string intersect_file() const override {
    return "techniques/relief_robust/relief_robust.glsl";
  }
  void bind_resources(GLuint) const override { glBindTextureUnit(4, texture_); }

 private:
  // The precompute's options, read when created.
  SafetyRadiusOptions radius_options() const {
    SafetyRadiusOptions o;
    o.error_allowed = param<double>("error_allowed");
    o.directions = param<int>("directions");
    o.max_radius = param<int>("max_radius");
    o.ignore_blocked = param<bool>("ignore_blocked");
    o.max_over_directions = param<bool>("max_over_directions");
    return o;
  }
  const SafetyRadiusOptions options_ = radius_options();
  SafetyRadii radii_;
  GLuint texture_ = 0;
};

RL_REGISTER_TECHNIQUE(ReliefRobust);

}  // namespace rl
