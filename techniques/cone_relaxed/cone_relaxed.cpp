// Relaxed cone step mapping (Policarpo & Oliveira 2007), conservative cones (Dummer 2006) as an
// option.
#include "cone_map.h"
#include "technique/shader_technique.h"

namespace rl {

class ConeRelaxed final : public Described<ConeRelaxed, ShaderTechnique> {
 public:
  using Described::Described;
  ~ConeRelaxed() override {
    if (texture_) glDeleteTextures(1, &texture_);
  }
  static TechniqueInfo describe() {
    return {.name = "cone_relaxed",
            .title = "Relaxed cone step mapping (cone steps, then binary search)",
            .citation =
                "Policarpo & Oliveira 2007, 'Relaxed Cone Stepping for Relief Mapping', GPU Gems "
                "3, chapter 18; conservative cones: Dummer 2006, 'Cone Step Mapping'",
            .effects = {Effect::SelfShadow, Effect::DepthCorrect, Effect::AmbientOcclusion,
                        Effect::SceneShadows},
            .params = {{.name = "cone_steps",
                        .kind = ParamKind::Int,
                        .default_value = 32,
                        .min_value = 1,
                        .max_value = 4096,
                        .doc = "cone steps along the ray (most rays stop after a few; the cap is "
                               "for grazing rays "
                               "crawling past features)",
                        .define = "RL_CONE_STEPS"},
                       binary_steps_param(6, "binary search steps over the last cone step"),
                       {.name = "relaxed",
                        .kind = ParamKind::Bool,
                        .default_value = 1,
                        .min_value = 0,
                        .max_value = 1,
                        .doc = "relaxed cones (GPU Gems 3); 0 = conservative cones (Dummer)"},
                       {.name = "directions",
                        .kind = ParamKind::Int,
                        .default_value = 32,
                        .min_value = 4,
                        .max_value = 256,
                        .doc = "azimuths the cone map precompute scans per texel"}},
            .draws = {.proxies = {Proxy::Base, Proxy::Box}},
            .contract = {.answer = Answer::Converging,
                         .max_fetches =
                             [](const RayQuery& q) {
                               return q.param("cone_steps") + q.param("binary_steps") + 2;
                             },
                         .max_fetches_formula = "cone_steps + binary_steps, + 2 to shade",
                         .knobs = {{"cone_steps"},
                                   {"binary_steps"},
                                   {"directions"},
                                   {"relaxed", /*larger_is_finer=*/false}},
                         .finest = {{"cone_steps", 4096},
                                    {"binary_steps", 16},
                                    {"directions", 64},
                                    {"relaxed", 0}},
                         .accuracy =
                             "conservative cones (relaxed = 0) never step over the surface, so the "
                             "steps converge on the first crossing; relaxed cones only promise one "
                             "crossing per step to rays through the top point above the texel, and "
                             "a grazing ray can enter and leave the surface within one step"}};
  }

  void prepare(const ReliefMap& map) override {
    cones_ = cached_cone_map(map, options_);
    const std::vector<float> ratio = ratios_safe_under_filtering(cones_);
    std::vector<glm::vec2> texels(ratio.size());
    for (size_t i = 0; i < texels.size(); ++i) texels[i] = {map.relief[i].a, ratio[i]};
    if (texture_) glDeleteTextures(1, &texture_);
    glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
    glTextureStorage2D(texture_, 1, GL_RG32F, map.width, map.height);
    glTextureSubImage2D(texture_, 0, 0, 0, map.width, map.height, GL_RG, GL_FLOAT, texels.data());
    glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture_, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(texture_, GL_TEXTURE_WRAP_T, GL_REPEAT);
  }
  size_t memory_bytes() const override { return cones_.ratio.size() * 2 * sizeof(float); }
  bool prepared_from_cache() const override { return cones_.from_cache; }
  const ConeMap& cones() const { return cones_; }

 protected:
  std::string intersect_file() const override {
    return "techniques/cone_relaxed/cone_relaxed.glsl";
  }
  void bind_resources(GLuint) const override { glBindTextureUnit(4, texture_); }

 private:
  const ConeMapOptions options_{.relaxed = param<bool>("relaxed"),
                                .directions = param<int>("directions")};
  ConeMap cones_;
  GLuint texture_ = 0;
};

RL_REGISTER_TECHNIQUE(ConeRelaxed);

}  // namespace rl
