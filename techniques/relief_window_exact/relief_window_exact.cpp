// Window-pyramid exact search: float-only empty-space skipping, exact ray-patch solve per cell.
#include <algorithm>
#include <cmath>
#include <vector>

#include "relief/min_depth_pyramid.h"
#include "relief/window_pyramid.h"
#include "technique/shader_technique.h"

namespace rl {

class ReliefWindowExact final : public Described<ReliefWindowExact, ShaderTechnique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {
        .name = "relief_window_exact",
        .title =
            "Window-pyramid exact search (float-only empty-space skipping, exact ray-patch "
            "solve per cell)",
        .citation =
            "Beyond the published work: the empty-space skipping of Tevs, Ihrke & "
            "Seidel 2008's maximum mipmaps without node alignment, over the bilinear "
            "cells, with relief_exact_bilinear's exact solve",
        .effects = {Effect::SelfShadow, Effect::DepthCorrect, Effect::AmbientOcclusion,
                    Effect::SceneShadows},
        .params = {{.name = "start_level",
                    .kind = ParamKind::Int,
                    .default_value = 2,
                    .min_value = 0,
                    .max_value = 16,
                    .doc = "level of the first step (2^level texels along the ray's faster "
                           "axis), at most the pyramid's coarsest",
                    .define = "RL_START_LEVEL"},
                   {.name = "climb_after",
                    .kind = ParamKind::Int,
                    .default_value = 3,
                    .min_value = 1,
                    .max_value = 4,
                    .doc = "steps taken at a level before the search tries the next one up "
                           "(1: after every step, as maximum-mipmap traversals do; more saves "
                           "the failing tries of a ray that runs close to the surface)",
                    .define = "RL_CLIMB_AFTER"},
                   {.name = "windows_by_way",
                    .kind = ParamKind::Int,
                    .default_value = 1,
                    .min_value = 0,
                    .max_value = 1,
                    .doc = "1: a window per quadrant of the ray's direction, two blocks wide "
                           "per axis (4x the memory); 0: one window for any direction, three "
                           "blocks wide, so steps are turned away more often",
                    .define = "RL_WINDOWS_BY_WAY"},
                   {.name = "solve_texels",
                    .kind = ParamKind::Int,
                    .default_value = 8,
                    .min_value = 1,
                    .max_value = 16,
                    .doc = "texels of the ray (along its faster axis) whose cells are solved "
                           "when even a one-texel step may hit, before the window is read "
                           "again (1: that step's texel only)",
                    .define = "RL_SOLVE_TEXELS"}},
        .draws = {.proxies = {Proxy::Base, Proxy::Box}},
        .contract = {.answer = Answer::Exact,
                     .max_fetches = [](const RayQuery& q) { return window_steps(q) + 2; },
                     .max_fetches_formula = "5 x (texels crossed along the faster axis + 2) + "
                                            "start_level (a window read per step, a gather per "
                                            "cell solved), + 2 to shade",
                     .accuracy = "the first hit on the bilinear surface, up to float rounding"}};
  }
  ~ReliefWindowExact() override {
    if (texture_) glDeleteTextures(1, &texture_);
  }
  size_t memory_bytes() const override { return bytes_; }

  // Each step advances at least a texel along the faster axis (a climb) or descends, and
  // descents are at most the climbs plus the first level; a solved stretch of n texels
  // gathers at most 3n + 1 cells after its one window read, at most 4 per texel.
  static double window_steps(const RayQuery& q) {
    const double texels = std::floor(std::max(q.span_texels.x, q.span_texels.y)) + 2;
    return std::min(4 * kWalkCellCap, 5 * texels + q.param("start_level"));
  }

  void prepare(const ReliefMap& map) override {
    // The cells' least corner depths, lowered by the pyramid's default margin so that a GPU's
    // own conversion of 8-bit depths never puts a corner above its bound.
    const std::vector<float> cells = build_min_depth_pyramid(map).level[0];
    top_ = quadtree_levels(map.width, map.height) - 1;
    if (texture_) glDeleteTextures(1, &texture_);
    // Layer = the ray's way along x (1: negative) + 2 x its way along y; one layer for either.
    const int layers = windows_by_way_ ? 4 : 1;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &texture_);
    glTextureStorage3D(texture_, top_ + 1, GL_R32F, map.width, map.height, layers);
    bytes_ = 0;
    for (int k = 0; k <= top_; ++k) {
      const int b = 1 << k;
      for (int layer = 0; layer < layers; ++layer) {
        const int way_x = layers == 1 ? 0 : layer & 1 ? -1 : 1;
        const int way_y = layers == 1 ? 0 : layer & 2 ? -1 : 1;
        const std::vector<float> level =
            window_level(cells, map.width, map.height, b, way_x, way_y);
        glTextureSubImage3D(texture_, k, 0, 0, layer, map.width / b, map.height / b, 1, GL_RED,
                            GL_FLOAT, level.data());
        bytes_ += level.size() * sizeof(float);
      }
    }
    glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(texture_, GL_TEXTURE_MAX_LEVEL, top_);
  }

 protected:
  std::string intersect_file() const override {
    return "techniques/relief_window_exact/relief_window_exact.glsl";
  }
  void bind_resources(GLuint program) const override {
    glBindTextureUnit(4, texture_);
    glProgramUniform1f(program, glGetUniformLocation(program, "rl_window_top"), float(top_));
  }

 private:
  const bool windows_by_way_ = param<int>("windows_by_way") != 0;  // an int switch, 0 or 1
  GLuint texture_ = 0;
  int top_ = 0;
  size_t bytes_ = 0;
};

RL_REGISTER_TECHNIQUE(ReliefWindowExact);

}  // namespace rl
