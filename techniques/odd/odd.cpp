// Omni-directional displacement maps (chapter 5, "Omni-directional displacement maps",
// Listing 5.9).
#include <stdexcept>

#include "core/error.h"
#include "gpu/scene_uniforms.h"
#include "odd_map.h"
#include "technique/shader_technique.h"

namespace rl {

class OmniDirectionalDisplacement final : public Described<OmniDirectionalDisplacement, Technique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {.name = "odd",
            .title = "Omni-directional displacement maps (4D map, no search)",
            .citation =
                "Chapter 5, 'Omni-directional displacement maps', Figures 5.29-5.33, "
                "Listing 5.9",
            .effects = {Effect::DepthCorrect},
            .params = {{.name = "spatial",
                        .kind = ParamKind::Int,
                        .default_value = 32,
                        .min_value = 1,
                        .max_value = 256,
                        .doc = "super pixels per tile side (X = Y): rays start at their centres"},
                       {.name = "directions",
                        .kind = ParamKind::Int,
                        .default_value = 16,
                        .min_value = 1,
                        .max_value = 64,
                        .doc = "stored directions per angle (A = B), at the centres of a grid "
                               "over a, b in [0, pi]"},
                       {.name = "direction_major",
                        .kind = ParamKind::Bool,
                        .default_value = 1,
                        .min_value = 0,
                        .max_value = 1,
                        .doc = "memory order (a, b, x, y) (Figure 5.31; the hardware then "
                               "filters space) or (x, y, a, b) (filters directions)",
                        .define = "RL_ODD_DIRECTION_MAJOR",
                        .define_when_set = true},
                       {.name = "interpolate",
                        .kind = ParamKind::Bool,
                        .default_value = 0,
                        .min_value = 0,
                        .max_value = 1,
                        .doc = "blend the four nearest cells of the floored pair too (4 "
                               "fetches): directions in (a, b, x, y), super pixels in "
                               "(x, y, a, b)",
                        .define = "RL_ODD_INTERPOLATE",
                        .define_when_set = true}},
            .draws = {.reads = {Representation::Heightfield}, .projections = {Projection::Plain}},
            .contract = {.answer = Answer::Approximation,
                         .max_fetches =
                             [](const RayQuery& q) {
                               return (q.param("interpolate") != 0 ? 4 : 1) + 1;
                             },
                         .max_fetches_formula = "1 (4 with interpolate), + 1 to shade",
                         .knobs = {{"spatial"}, {"directions"}},
                         .accuracy = "exact at a super pixel's centre in a sampled direction; "
                                     "elsewhere that sample's depth",
                         .hits_from_inside = false},
            .columns = {{"odd_missed_rays", "rays",
                         "rays of the 4D map's precompute that left the relief without a hit "
                         "(stored at depth 1)"}}};
  }

  static void validate(const ParamValues& p, const std::string& where) {
    const double texels = p.at("spatial") * p.at("directions");
    if (texels > 16384)
      throw ConfigError(where + ": odd's 4D map would be " + std::to_string(long(texels)) +
                        " texels square (spatial x directions); GL guarantees 16384");
  }

  ~OmniDirectionalDisplacement() override {
    if (texture_) glDeleteTextures(1, &texture_);
  }

  // The map depends on the world's proportions (its directions are the world's): built here for
  // the scene's, timed as precompute.
  void prepare_scene(const SceneDesc& scene, const ReliefMap& map) override {
    const PlanarBase base = planar_base(scene);
    build(map, {scene.depth / glm::length(base.dpdu()), scene.depth / glm::length(base.dpdv())});
  }

  void render(const FrameInput& frame, RenderTarget::Kind target) override {
    const SceneDesc& s = frame.scene;
    if (!texture_) prepare_scene(s, frame.map);
    ProgramDesc d = program();
    d.vertex_file = "harness/glsl/base.vert";
    if (target == RenderTarget::Kind::GBuffer) d.defines["RL_GBUFFER"] = "1";
    const GLuint p = ShaderLibrary::shared().program(d);
    glUseProgram(p);
    set_scene_uniforms(p, s, frame.camera);
    set_uniform(p, "rl_depth_scale", s.depth);
    set_map_uniforms(p);
    frame.relief.bind();
    glBindTextureUnit(4, texture_);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    frame.base.draw();
  }

  std::vector<ProbeHit> probe(const ReliefMap& map, const GpuRelief& relief,
                              const std::vector<ProbeRay>& rays, glm::dvec2 depth_aspect) override {
    if (rays.empty()) return {};
    if (!texture_ || odd_.depth_aspect != depth_aspect) build(map, depth_aspect);
    ProgramDesc d = program();
    d.vertex_file = "harness/glsl/fullscreen.vert";
    d.defines["RL_PROBE"] = "1";
    const GLuint p = ShaderLibrary::shared().program(d);
    set_map_uniforms(p);
    set_uniform(p, "rl_depth_aspect", depth_aspect);
    const GBuffer out = run_probe_pass(p, rays, [&] {
      relief.bind();
      glBindTextureUnit(4, texture_);
    });
    return decode_probe_hits(out, rays.size());
  }

  size_t memory_bytes() const override { return odd_.bytes(); }
  std::vector<std::pair<std::string, double>> frame_columns() const override {
    return {{"odd_missed_rays", double(odd_.missed_rays)}};
  }

 private:
  void build(const ReliefMap& map, glm::dvec2 depth_aspect) {
    odd_ = build_odd_map(map, size_, direction_major_, depth_aspect);
    if (texture_) glDeleteTextures(1, &texture_);
    glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
    glTextureStorage2D(texture_, 1, GL_RGBA8, odd_.width, odd_.height);
    glTextureSubImage2D(texture_, 0, 0, 0, odd_.width, odd_.height, GL_RGBA, GL_FLOAT,
                        odd_.texels.data());
    // The GPU has it now; the float copy is 4x the texture (1 GiB at 256^2 x 32^2).
    odd_.texels = {};
    // Bilinear within the inner pair; lookups clamp to its texel centres, so no tile bleeds.
    glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  void set_map_uniforms(GLuint p) const {
    glProgramUniform1i(p, glGetUniformLocation(p, "rl_odd_spatial"), odd_.size.spatial);
    glProgramUniform1i(p, glGetUniformLocation(p, "rl_odd_directions"), odd_.size.directions);
  }
  ProgramDesc program() const {
    ProgramDesc d;
    d.owner = info().name;
    d.fragment_files = {"techniques/odd/odd.glsl"};
    d.defines = declared_defines();
    return d;
  }

  const OddSize size_{param<int>("spatial"), param<int>("directions")};
  const bool direction_major_ = param<bool>("direction_major");
  OddMap odd_;
  GLuint texture_ = 0;
};

RL_REGISTER_TECHNIQUE(OmniDirectionalDisplacement);

}  // namespace rl
