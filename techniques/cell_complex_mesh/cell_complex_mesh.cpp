// Relief mapping on cubic cell complexes, geometry-based rendering (Apaza & Andujar,
// Section 3.5.1): the distance maps unprojected into triangles, level of detail by mip level;
// and the input mesh rasterised, the baseline of Table 2.
#include <stdexcept>

#include "gl/shader_library.h"
#include "gpu/gpu_cell_complex.h"
#include "gpu/scene_uniforms.h"
#include "gpu/triangle_buffers.h"
#include "relief/cell_complex.h"
#include "technique/technique.h"

namespace rl {

// Draws a triangle mesh in the cube's texture space with per-vertex normals and colours from
// a CellMesh (the shaders of this folder): the reconstruction below and the mesh baseline.
class CellTriangles : public Technique {
 public:
  using Technique::Technique;

  void render(const FrameInput& frame, RenderTarget::Kind target) override {
    if (!frame.relief.cells() || !frame.map.cells)
      throw std::logic_error(info().name + " rendered on a scene without a cell complex");
    ProgramDesc d;
    d.owner = info().name;
    d.vertex_file = "techniques/cell_complex_mesh/cell_mesh_vert.glsl";
    d.fragment_files = {"techniques/cell_complex_mesh/cell_mesh_frag.glsl"};
    if (target == RenderTarget::Kind::GBuffer) d.defines["RL_GBUFFER"] = "1";
    const GLuint p = ShaderLibrary::shared().program(d);
    glUseProgram(p);
    set_scene_uniforms(p, frame.scene, frame.camera);
    set_cell_complex_uniforms(p, frame.scene, frame.camera, *frame.map.cells,
                              *frame.relief.cells());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);  // windings are the texel order's or the file's, not outward
    buffers_.draw();
  }

  // No search to probe: the surface is rasterised.
  std::vector<ProbeHit> probe(const ReliefMap&, const GpuRelief&, const std::vector<ProbeRay>&,
                              glm::dvec2) override {
    throw std::logic_error(info().name + " rasterises its surface; it has no ray search to probe");
  }

  size_t memory_bytes() const override { return buffers_.bytes(); }

 protected:
  void upload(const CellMesh& mesh) {
    buffers_ = TriangleBuffers(mesh.position, mesh.normal, mesh.color, mesh.triangles);
  }

 private:
  TriangleBuffers buffers_;
};

class CellComplexMesh final : public Described<CellComplexMesh, CellTriangles> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {.name = "cell_complex_mesh",
            .title = "Cubic cell complexes, geometry-based rendering (unprojected texels)",
            .citation = "Apaza & Andujar, 'Relief mapping on cubic cell complexes', Section 3.5.1",
            .effects = {Effect::DepthCorrect},
            .params = {{.name = "lod",
                        .kind = ParamKind::Int,
                        .default_value = 0,
                        .min_value = 0,
                        .max_value = 10,
                        .doc = "mip level of the distance maps: one vertex per 2^lod x 2^lod "
                               "texels (0 = every texel)"},
                       {.name = "max_edge_texels",
                        .kind = ParamKind::Float,
                        .default_value = 6,
                        .min_value = 1.5,
                        .max_value = 1e6,
                        .doc = "a triangle with an edge longer than this many texels of its level "
                               "is dropped: it would join two sheets across a depth discontinuity "
                               "(at least 1.5: below the diagonal of a texel, sqrt 2, every "
                               "triangle went and nothing was drawn)"}},
            .draws = {.reads = {Representation::CellComplex}, .proxies = {Proxy::Base, Proxy::Box}},
            .contract = {.answer = Answer::Approximation,
                         .max_fetches = [](const RayQuery&) { return 0; },
                         .max_fetches_formula = "0: rasterised triangles, shaded from vertices",
                         .knobs = {{"lod", false}},
                         .accuracy = "the distance maps' surface at 2^lod texels per vertex, "
                                     "interpolated linearly between texels",
                         .ray_probe = false,
                         .hits_from_inside = false}};
  }

  void prepare(const ReliefMap& map) override {
    if (!map.cells) throw std::logic_error("cell_complex_mesh prepared without a cell complex");
    upload(reconstruct_cell_mesh(*map.cells, lod_, max_edge_texels_));
  }

 private:
  const int lod_ = param<int>("lod");
  const double max_edge_texels_ = param<double>("max_edge_texels");
};

// The baseline the paper compares against (Section 4, Table 2): the input mesh itself,
// rasterised with its triangles' normals, as it is in the cell complex's texture space.
class CellSourceMesh final : public Described<CellSourceMesh, CellTriangles> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {
        .name = "cell_source_mesh",
        .title = "The cell complex's input mesh, rasterised (baseline)",
        .citation = "Apaza & Andujar, Section 4 (rendering the input model, Table 2's comparison)",
        .effects = {Effect::DepthCorrect},
        .params = {},
        .draws = {.reads = {Representation::CellComplex}, .proxies = {Proxy::Base, Proxy::Box}},
        .contract = {.answer = Answer::Exact,
                     .max_fetches = [](const RayQuery&) { return 0; },
                     .max_fetches_formula = "0: rasterised triangles",
                     .accuracy = "the mesh the truth traces, up to the rasteriser's rounding",
                     .ray_probe = false,
                     .hits_from_inside = false}};
  }

  void prepare(const ReliefMap& map) override {
    if (!map.cells) throw std::logic_error("cell_source_mesh prepared without a cell complex");
    const TriangleMesh& src = map.cells->mesh();
    CellMesh m;
    m.position.reserve(3 * src.triangles.size());
    for (size_t i = 0; i < src.triangles.size(); ++i) {
      const glm::uvec3 t = src.triangles[i];
      const glm::vec3 a = src.positions[t.x], b = src.positions[t.y], c = src.positions[t.z];
      const glm::vec3 n = glm::cross(b - a, c - a);
      const glm::vec3 color = src.triangle_colors.empty() ? kCellAlbedo : src.triangle_colors[i];
      for (const glm::vec3& p : {a, b, c}) {
        m.position.push_back(p);
        m.normal.push_back(n);  // unnormalised: the shader normalises (and faces it)
        m.color.push_back(color);
      }
      const unsigned k = unsigned(3 * i);
      m.triangles.push_back({k, k + 1, k + 2});
    }
    upload(m);
  }
};

RL_REGISTER_TECHNIQUE(CellComplexMesh);
RL_REGISTER_TECHNIQUE(CellSourceMesh);

}  // namespace rl
