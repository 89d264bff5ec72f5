// Relief mapping on cubic cell complexes, ray casting (Apaza & Andujar, Section 3.5.2).
#include <cmath>
#include <stdexcept>

#include "gpu/gpu_cell_complex.h"
#include "gpu/scene_uniforms.h"
#include "relief/cell_complex.h"
#include "technique/texture_space_technique.h"

namespace rl {
namespace {

// The proxy (Section 3.5.2, CPU step 2): the faces of grey cells that border a white cell or
// the grid, counter-clockwise seen from outside in world space (texture space is mirrored in
// depth), as texture-space triangles.
std::vector<glm::vec3> proxy_triangles(const CellComplex& cc) {
  std::vector<glm::vec3> tris;
  const int n = cc.grid();
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (cc.cell(i, j, k).state != CellState::Grey) continue;
        for (int f = 0; f < 6; ++f) {
          int nb[3] = {i, j, k};
          nb[f / 2] += f % 2 ? 1 : -1;
          const bool border = nb[f / 2] < 0 || nb[f / 2] >= n ||
                              cc.cell(nb[0], nb[1], nb[2]).state == CellState::White;
          if (border) append_cube_face(tris, {i, j, k}, f, n);
        }
      }
  return tris;
}

}  // namespace

class CellComplexRaycast final : public Described<CellComplexRaycast, TextureSpaceTechnique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {.name = "cell_complex",
            .title = "Relief mapping on cubic cell complexes (ray casting)",
            .citation = "Apaza & Andujar, 'Relief mapping on cubic cell complexes', Section 3.5.2",
            .effects = {Effect::DepthCorrect},
            .params = {{.name = "steps_per_cell",
                        .kind = ParamKind::Int,
                        .default_value = 8,
                        .min_value = 1,
                        .max_value = 512,
                        .doc = "linear search samples per cell side along the ray (the search "
                               "runs until the ray leaves the grey cells)",
                        .define = "RL_STEPS_PER_CELL"},
                       binary_steps_param(6, "binary search refinements after the linear search")},
            .draws = {.reads = {Representation::CellComplex}, .proxies = {Proxy::Base, Proxy::Box}},
            .contract = {
                .answer = Answer::Converging,
                .max_fetches =
                    [](const RayQuery& q) {
                      const double steps =
                          std::ceil(1.7320508 * q.grid_cells * q.param("steps_per_cell")) + 2;
                      return 2 * (steps + q.param("binary_steps")) + 2;
                    },
                .max_fetches_formula = "2 x (ceil(sqrt(3) x grid cells x steps_per_cell) + 2 + "
                                       "binary_steps), + 2 to shade",
                .knobs = {{"steps_per_cell"}, {"binary_steps"}},
                .finest = {{"steps_per_cell", 64}, {"binary_steps", 16}},
                .accuracy = "the first entry into the cells' solid to within one step (a cell / "
                            "steps_per_cell) / 2^binary_steps along the ray, where no part is "
                            "thinner than a step"}};
  }

  void prepare(const ReliefMap& map) override {
    if (!map.cells) throw std::logic_error("cell_complex prepared without a cell complex");
    proxy_.set(proxy_triangles(*map.cells));
  }
  size_t memory_bytes() const override { return proxy_.bytes(); }

 protected:
  std::string missing_data(const ReliefMap& map, const GpuRelief& relief) const override {
    return map.cells && relief.cells() ? "" : "a cell complex";
  }
  void set_frame_uniforms(GLuint p, const FrameInput& frame) const override {
    set_cell_complex_uniforms(p, frame.scene, frame.camera, *frame.map.cells,
                              *frame.relief.cells());
  }
  // Probe rays are in the cube's texture space (u, v, depth), any direction; t counts
  // multiples of the direction. The search runs along the whole chord of the grid.
  void set_probe_uniforms(GLuint p, const ReliefMap& map, const GpuRelief& relief) const override {
    set_cell_table_uniforms(p, *map.cells, *relief.cells());
  }
  ProgramDesc program() const override {
    ProgramDesc d;
    d.owner = info().name;
    d.fragment_files = {"techniques/cell_complex/cell_complex_main.glsl"};
    return d;
  }
};

RL_REGISTER_TECHNIQUE(CellComplexRaycast);

}  // namespace rl
