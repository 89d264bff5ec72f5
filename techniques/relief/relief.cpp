// Relief mapping with linear + binary search, book chapter 5 Listings 5.3 / 5.4.
#include <cmath>
#include <string>

#include "gpu/mipmapped_relief.h"
#include "gpu/packed_relief.h"
#include "technique/shader_technique.h"

namespace rl {

class ReliefMapping final : public Described<ReliefMapping, ShaderTechnique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {
        .name = "relief",
        .title = "Relief mapping (linear + binary search)",
        .citation =
            "Book chapter 5, 'Relief Texture mapping', Listings 5.3 and 5.4 "
            "(Policarpo, Oliveira & Comba 2005)",
        .effects = {Effect::SelfShadow, Effect::DepthCorrect, Effect::AmbientOcclusion,
                    Effect::SceneShadows},
        .params =
            {linear_steps_param(
                 10,
                 "linear search steps through the depth range (Listing 5.3: 10, or 20 in its "
                 "double-precision variant); 1 = no linear search, the binary chop alone "
                 "(Figure 5.12)"),
             binary_steps_param(
                 5, "binary search refinements after the linear search (Listing 5.3: 5)"),
             {.name = "mipmap",
              .kind = ParamKind::Bool,
              .default_value = 0,
              .min_value = 0,
              .max_value = 1,
              .doc = "1: normals and depths read from mip-mapped copies at the pixel's footprint "
                     "(chapter 5, 'Texture filtering and mip-mapping'); 0: level 0, the surface "
                     "the truth reconstructs",
              .neutral_default = true,
              .define = "RL_MIPMAPPED_RELIEF",
              .define_when_set = true},
             {.name = "color_mipmap",
              .kind = ParamKind::Bool,
              .default_value = 0,
              .min_value = 0,
              .max_value = 1,
              .doc = "1: the colour alone read from its mip chain at the pixel's footprint, the "
                     "geometry at level 0 (Baboud & Decoret 2006, Section 6); 0: level 0, as the "
                     "truth shades it",
              .neutral_default = true,
              .define = "RL_COLOR_MIPMAP",
              .define_when_set = true},
             {.name = "ao_packed",
              .kind = ParamKind::Bool,
              .default_value = 0,
              .min_value = 0,
              .max_value = 1,
              .doc = "1: the AO map in the relief texture's blue channel, the normal's x and y in "
                     "red and green and its z rebuilt (Limberger et al., Section IV), so the AO "
                     "costs no fetch of its own; 0: a texture of its own",
              .neutral_default = true,
              .define = "RL_AO_PACKED",
              .define_when_set = true}},
        .draws = {.reads = {Representation::Heightfield, Representation::Layers,
                            Representation::MetaRuntime},
                  .proxies = {Proxy::Base, Proxy::Box}},
        .contract = {.answer = Answer::Converging,
                     .max_fetches =
                         [](const RayQuery& q) {
                           return q.param("linear_steps") - 1 + q.param("binary_steps") + 2;
                         },
                     .max_fetches_formula = "linear_steps - 1 + binary_steps, + 2 to shade",
                     .knobs = linear_binary_knobs(),
                     .finest = linear_binary_finest(),
                     .t_error = linear_binary_t_error,
                     .accuracy =
                         "the first crossing to within one linear step / 2^binary_steps along the "
                         "ray, on surfaces with no feature thinner than a linear step",
                     .t_resolution = one_linear_step},
        // A meta-relief combined per fetch reads its layers, which have no mip levels.
        .setting_cannot_render = [](const ParamValues& setting, const SceneDesc& scene) {
          if (setting.at("mipmap") != 0 && setting.at("ao_packed") != 0)
            return std::string("mipmap = 1 and ao_packed = 1 each read a map of their own");
          return (setting.at("mipmap") != 0 || setting.at("ao_packed") != 0) && scene.meta.runtime()
                     ? std::string(
                           "mipmap = 1 and ao_packed = 1 read one map, and this scene's "
                           "meta-relief is combined per fetch; set combine = \"baked\" "
                           "in its meta_relief")
                     : std::string();
        }};
  }
  void prepare(const ReliefMap& map) override {
    if (mipmapped_) mipmaps_.upload(map);
    if (color_mipmapped_) color_mips_.upload(map);
    if (packed_ao_) packed_.upload(map);
  }
  size_t memory_bytes() const override {
    return mipmaps_.bytes() + color_mips_.bytes() + packed_.bytes();
  }

 protected:
  std::string intersect_file() const override { return "techniques/relief/relief.glsl"; }
  Defines parameter_defines() const override {
    Defines d;
    // Either mip chain needs the footprint's level of detail.
    if (mipmapped_ || color_mipmapped_) d["RL_MIPMAP"] = "1";
    return d;
  }
  void bind_resources(GLuint) const override {
    if (mipmapped_) mipmaps_.bind();
    if (color_mipmapped_) color_mips_.bind();
    if (packed_ao_) packed_.bind();
  }

 private:
  const bool mipmapped_ = param<bool>("mipmap");
  const bool color_mipmapped_ = param<bool>("color_mipmap");
  const bool packed_ao_ = param<bool>("ao_packed");
  MipmappedRelief mipmaps_;
  MipmappedRelief color_mips_{MipmappedRelief::Channel::Color};
  PackedRelief packed_;
};

RL_REGISTER_TECHNIQUE(ReliefMapping);

}  // namespace rl
