// Relief mapping with double depth values, book chapter 5 (after Angel & Christ).
#include <cmath>
#include "technique/shader_technique.h"

namespace rl {

class DoubleDepth final : public Described<DoubleDepth, ShaderTechnique> {
 public:
  using Described::Described;
  ~DoubleDepth() override {
    if (texture_) glDeleteTextures(1, &texture_);
  }
  static TechniqueInfo describe() {
    return {.name = "double_depth",
            .title = "Relief mapping with double depth (front and back depth in one map)",
            .citation =
                "Book chapter 5, 'Single RTM with Double Depth values (restricted 3D "
                "objects)', Figures 5.14-5.15 (after Angel & Christ)",
            .effects = {Effect::SelfShadow, Effect::DepthCorrect, Effect::SceneShadows},
            .params = {linear_steps_param(
                           32, "linear search samples down to depth 1 (Listing 5.3's search)"),
                       binary_steps_param(5, "binary search refinements (Listing 5.3: 5)")},
            .contract = {.answer = Answer::Converging,
                         .surface = Surface::TexelColumns,
                         .max_fetches = linear_binary_fetches_shaded,
                         .max_fetches_formula = "linear_steps + binary_steps, + 2 to shade",
                         .knobs = linear_binary_knobs(),
                         .finest = linear_binary_finest(),
                         .t_error = linear_binary_t_error,
                         .accuracy =
                             "the first entry into the solid between the two depths to within one "
                             "linear step / 2^binary_steps along the ray, on solids with no part "
                             "thinner than a linear step",
                         .t_resolution = one_linear_step}};
  }

  // One RGBA texel per texel: the front surface's normal x and y, the front depth (the first
  // layer) and the back depth (the last layer of an even count; 1 where the column is solid
  // to the bottom: a heightfield, or an odd count).
  void prepare(const ReliefMap& map) override {
    const size_t texels = size_t(map.width) * map.height;
    std::vector<glm::vec4> data(texels);
    for (size_t i = 0; i < texels; ++i) {
      const glm::vec3 n = map.layers.empty() ? glm::vec3(decode_normal(glm::dvec4(map.relief[i])))
                                             : map.layers.normal[i];
      float front = map.relief[i].a, back = 1.0f;
      if (!map.layers.empty()) {
        const int used = map.layers.used(i);
        front = used ? map.layers.depth[i] : 1.0f;
        if (used && used % 2 == 0) back = map.layers.depth[(used - 1) * texels + i];
      }
      data[i] = glm::vec4(n.x * 0.5f + 0.5f, n.y * 0.5f + 0.5f, front, back);
    }
    if (texture_) glDeleteTextures(1, &texture_);
    glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
    glTextureStorage2D(texture_, 1, map.quantized ? GL_RGBA8 : GL_RGBA32F, map.width, map.height);
    glTextureSubImage2D(texture_, 0, 0, 0, map.width, map.height, GL_RGBA, GL_FLOAT, data.data());
    // Nearest, as for the multilayer maps: filtering front and back depths across an object's
    // edge would build skins.
    glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(texture_, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(texture_, GL_TEXTURE_WRAP_T, GL_REPEAT);
    bytes_ = texels * (map.quantized ? 4 : 16);
    floor_ = layered_floor_define(map);
  }
  size_t memory_bytes() const override { return bytes_; }

 protected:
  std::string intersect_file() const override {
    return "techniques/double_depth/double_depth.glsl";
  }
  Defines parameter_defines() const override { return floor_; }
  void bind_resources(GLuint) const override { glBindTextureUnit(4, texture_); }

 private:
  GLuint texture_ = 0;
  size_t bytes_ = 0;
  Defines floor_;  // RL_LAYERED_FLOOR on a multilayer map
};

RL_REGISTER_TECHNIQUE(DoubleDepth);

}  // namespace rl
