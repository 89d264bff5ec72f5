// Relief mapping of non-height-field surface details, Policarpo & Oliveira 2006.
#include <algorithm>
#include <cmath>

#include "gpu/mipmapped_relief.h"
#include "technique/shader_technique.h"

namespace rl {

class Multilayer final : public Described<Multilayer, ShaderTechnique> {
 public:
  using Described::Described;
  ~Multilayer() override { release(); }
  static TechniqueInfo describe() {
    return {
        .name = "multilayer",
        .title = "Multilayer relief mapping (non-height-field details, up to 8 layers)",
        .citation =
            "Policarpo & Oliveira 2006, 'Relief Mapping of Non-Height-Field Surface Details', "
            "Sections 3.1-3.2, Algorithms 1-2, Appendix A",
        .effects = {Effect::SelfShadow, Effect::Silhouette, Effect::DepthCorrect,
                    Effect::SceneShadows},
        .params = {linear_steps_param(32, "linear search samples down to depth 1 (Algorithm 1)"),
                   binary_steps_param(5, "binary search refinements (Algorithm 2; Appendix A: 5)"),
                   {.name = "linear_filter",
                    .kind = ParamKind::Bool,
                    .default_value = 0,
                    .min_value = 0,
                    .max_value = 1,
                    .doc = "sample layers with GL_LINEAR instead of the paper's nearest "
                           "(Section 6: filtering mixes surface and empty texels into skins)"},
                   {.name = "mipmap",
                    .kind = ParamKind::Bool,
                    .default_value = 0,
                    .min_value = 0,
                    .max_value = 1,
                    .doc = "Section 6's regular mip-mapping: depths and normals from mip chains "
                           "(each level the 2 x 2 average, empty texels' depth 1 included) at the "
                           "pixel's footprint, nearest within a level unless linear_filter; "
                           "colour at level 0",
                    .neutral_default = true,
                    .define = "RL_MIPMAP",
                    .define_when_set = true},
                   {.name = "interface_fix",
                    .kind = ParamKind::Bool,
                    .default_value = 1,
                    .min_value = 0,
                    .max_value = 1,
                    .doc = "Section 3.2: of the last inside and outside samples, keep the one "
                           "on the texel with more layers",
                    .define = "RL_INTERFACE_FIX"},
                   {.name = "grazing_bias",
                    .kind = ParamKind::Bool,
                    .default_value = 0,
                    .min_value = 0,
                    .max_value = 1,
                    .doc = "Appendix A's depth bias: search a relief 2 cos - cos^2 as deep (cos: "
                           "the view to the base normal), flatter at grazing views; not on "
                           "impostors or curved bases",
                    .define = "RL_GRAZING_BIAS"},
                   {.name = "two_pass",
                    .kind = ParamKind::Bool,
                    .default_value = 0,
                    .min_value = 0,
                    .max_value = 1,
                    .doc = "pattern on a closed curved base: draw front faces, then back faces "
                           "(Section 5's 2-pass rendering), not all faces in one pass"}},
        .draws = {.reads = {Representation::Heightfield, Representation::Layers,
                            Representation::Impostor}},
        .contract = {.answer = Answer::Converging,
                     .surface = Surface::TexelColumns,
                     .max_fetches =
                         [](const RayQuery& q) {
                           return (q.param("linear_steps") + q.param("binary_steps") + 1) *
                                      q.layer_groups +
                                  3;
                         },
                     .max_fetches_formula = "(linear_steps + binary_steps + 1) x layer groups, + 3 "
                                            "to shade",
                     .knobs = linear_binary_knobs(),
                     .finest = linear_binary_finest(),
                     .t_error = linear_binary_t_error,
                     .accuracy =
                         "the first entry into the solid to within one linear step / "
                         "2^binary_steps along the ray, on solids with no part or gap thinner "
                         "than a linear step",
                     .t_resolution = one_linear_step},
        .columns = {{"base_passes", "passes",
                     "passes over the base: 2 when a pattern on a closed curved base is "
                     "drawn front faces, then back faces"}}};
  }

  // Uploads the layers as the paper stores them: per group of four, one RGBA texel of depths,
  // one of normal x and one of normal y (z is rebuilt); colours one slice per layer. A map
  // without layers is its heightfield as one layer (Section 3: G, B, A = 1).
  void prepare(const ReliefMap& map) override {
    release();
    const size_t texels = size_t(map.width) * map.height;
    const int count = map.layers.empty() ? 1 : map.layers.count;
    groups_ = (count + 3) / 4;
    floor_ = layered_floor_define(map);
    auto depth_at = [&](int l, size_t i) {
      if (map.layers.empty()) return l == 0 ? map.relief[i].a : 1.0f;
      return l < count ? map.layers.depth[l * texels + i] : 1.0f;
    };
    auto normal_at = [&](int l, size_t i) {
      if (map.layers.empty())
        return l == 0 ? glm::vec3(decode_normal(glm::dvec4(map.relief[i]))) : glm::vec3(0, 0, 1);
      return l < count ? map.layers.normal[l * texels + i] : glm::vec3(0, 0, 1);
    };
    std::vector<glm::vec4> depth(texels * groups_), nx(depth.size()), ny(depth.size());
    std::vector<glm::vec4> color(texels * count);
    for (int g = 0; g < groups_; ++g)
      for (size_t i = 0; i < texels; ++i)
        for (int k = 0; k < 4; ++k) {
          const int l = 4 * g + k;
          depth[g * texels + i][k] = depth_at(l, i);
          const glm::vec3 n = normal_at(l, i);
          nx[g * texels + i][k] = n.x * 0.5f + 0.5f;
          ny[g * texels + i][k] = n.y * 0.5f + 0.5f;
        }
    // A heightfield's colour at the layers' texels (its colour map may have its own size).
    auto heightfield_color = [&](size_t i) {
      if (map.color_width == 0) return map.color[i];
      const double u = (double(i % size_t(map.width)) + 0.5) / map.width;
      const double v = (double(i / size_t(map.width)) + 0.5) / map.height;
      return glm::vec4(map.sample_color(u, v));
    };
    for (int l = 0; l < count; ++l)
      for (size_t i = 0; i < texels; ++i)
        color[l * texels + i] = map.layers.empty()
                                    ? heightfield_color(i)
                                    : glm::vec4(map.layers.color[l * texels + i], 1.0f);
    const GLenum format = map.quantized ? GL_RGBA8 : GL_RGBA32F;
    const GLenum filter = linear_filter_ ? GL_LINEAR : GL_NEAREST;
    const GLenum mip_filter = linear_filter_ ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_NEAREST;
    bytes_ = 0;
    // `mipmapped`: the full chain, each level the driver's 2 x 2 average of the one above.
    auto upload = [&](GLuint& tex, const std::vector<glm::vec4>& data, int slices, bool mipmapped) {
      const int levels = mipmapped ? mip_levels(map.width, map.height) : 1;
      glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &tex);
      glTextureStorage3D(tex, levels, format, map.width, map.height, slices);
      glTextureSubImage3D(tex, 0, 0, 0, 0, map.width, map.height, slices, GL_RGBA, GL_FLOAT,
                          data.data());
      if (mipmapped) glGenerateTextureMipmap(tex);
      glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, mipmapped ? mip_filter : filter);
      glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, filter);
      glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_REPEAT);
      glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_REPEAT);
      const size_t texel_bytes = size_t(slices) * (map.quantized ? 4 : 16);
      bytes_ +=
          mipmapped ? mip_chain_bytes(map.width, map.height, texel_bytes) : texels * texel_bytes;
    };
    upload(textures_[0], depth, groups_, mipmapped_);
    upload(textures_[1], nx, groups_, mipmapped_);
    upload(textures_[2], ny, groups_, mipmapped_);
    upload(textures_[3], color, count, false);
  }
  size_t memory_bytes() const override { return bytes_; }

 protected:
  std::string intersect_file() const override { return "techniques/multilayer/multilayer.glsl"; }
  Defines parameter_defines() const override {
    Defines d = {{"RL_LAYER_GROUPS", std::to_string(groups_)}};
    d.insert(floor_.begin(), floor_.end());
    return d;
  }
  bool two_pass() const override { return two_pass_; }
  // Section 5's two passes draw the base twice (front faces, then back faces): the image is the
  // same as one pass's, the rasterised work is not, so the row says how many passes it drew.
  void render(const FrameInput& frame, RenderTarget::Kind target) override {
    ShaderTechnique::render(frame, target);
    base_passes_ = two_pass() && variant_of(frame.scene).two_sided ? 2 : 1;
  }
  std::vector<std::pair<std::string, double>> frame_columns() const override {
    return {{"base_passes", double(base_passes_)}};
  }
  void bind_resources(GLuint) const override {
    for (int k = 0; k < 4; ++k) glBindTextureUnit(4 + k, textures_[k]);
  }

 private:
  const bool linear_filter_ = param<bool>("linear_filter");
  const bool mipmapped_ = param<bool>("mipmap");
  const bool two_pass_ = param<bool>("two_pass");

  void release() {
    for (GLuint& t : textures_)
      if (t) {
        glDeleteTextures(1, &t);
        t = 0;
      }
  }
  GLuint textures_[4] = {0, 0, 0, 0};
  int groups_ = 1;
  Defines floor_;  // RL_LAYERED_FLOOR on a multilayer map
  int base_passes_ = 1;
  size_t bytes_ = 0;
};

RL_REGISTER_TECHNIQUE(Multilayer);

}  // namespace rl
