// Relief mapping on cubic cell complexes, geometry-based rendering (Apaza & Andujar,
// Section 3.5.1): the distance maps unprojected into triangles, level of detail by mip level.
#include <stdexcept>

#include "gl/shader_library.h"
#include "relief/cell_complex.h"
#include "technique/gpu_cell_complex.h"
#include "technique/scene_uniforms.h"
#include "technique/technique.h"

namespace rl {

class CellComplexMesh final : public Described<CellComplexMesh, Technique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {
        .name = "cell_complex_mesh",
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
                    .min_value = 1,
                    .max_value = 1e6,
                    .doc = "a triangle with an edge longer than this many texels of its level "
                           "is dropped: it would join two sheets across a depth discontinuity"}},
        .cell_complex = true};
  }
  ~CellComplexMesh() override { release(); }

  void prepare(const ReliefMap& map) override {
    if (!map.cells) throw std::logic_error("cell_complex_mesh prepared without a cell complex");
    const CellMesh mesh =
        reconstruct_cell_mesh(*map.cells, int(param("lod")), param("max_edge_texels"));
    std::vector<glm::vec3> interleaved;
    for (size_t i = 0; i < mesh.position.size(); ++i)
      interleaved.insert(interleaved.end(), {mesh.position[i], mesh.normal[i], mesh.color[i]});
    release();
    glCreateVertexArrays(1, &vao_);
    glCreateBuffers(1, &vbo_);
    glCreateBuffers(1, &ibo_);
    glNamedBufferStorage(vbo_,
                         GLsizeiptr(std::max<size_t>(1, interleaved.size()) * sizeof(glm::vec3)),
                         interleaved.empty() ? nullptr : interleaved.data(), 0);
    glNamedBufferStorage(
        ibo_, GLsizeiptr(std::max<size_t>(1, mesh.triangles.size()) * sizeof(glm::uvec3)),
        mesh.triangles.empty() ? nullptr : mesh.triangles.data(), 0);
    glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, 3 * sizeof(glm::vec3));
    glVertexArrayElementBuffer(vao_, ibo_);
    for (GLuint a = 0; a < 3; ++a) {
      glEnableVertexArrayAttrib(vao_, a);
      glVertexArrayAttribFormat(vao_, a, 3, GL_FLOAT, GL_FALSE, a * sizeof(glm::vec3));
      glVertexArrayAttribBinding(vao_, a, 0);
    }
    indices_ = GLsizei(3 * mesh.triangles.size());
    bytes_ = interleaved.size() * sizeof(glm::vec3) + mesh.triangles.size() * sizeof(glm::uvec3);
  }

  void render(const FrameInput& frame, RenderTarget::Kind target) override {
    if (!frame.relief.cells() || !frame.map.cells)
      throw std::logic_error("cell_complex_mesh rendered on a scene without a cell complex");
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
    glDisable(GL_CULL_FACE);  // a face's triangles are wound by its texel order, not outward
    glBindVertexArray(vao_);
    glDrawElements(GL_TRIANGLES, indices_, GL_UNSIGNED_INT, nullptr);
  }

  // No search to probe: the surface is rasterised.
  std::vector<ProbeHit> probe(const ReliefMap&, const GpuRelief&, const std::vector<ProbeRay>&,
                              glm::dvec2) override {
    throw std::logic_error(
        "cell_complex_mesh rasterises its surface; it has no ray search to probe");
  }

  size_t memory_bytes() const override { return bytes_; }

 private:
  void release() {
    if (vao_) glDeleteVertexArrays(1, &vao_);
    if (vbo_) glDeleteBuffers(1, &vbo_);
    if (ibo_) glDeleteBuffers(1, &ibo_);
    vao_ = vbo_ = ibo_ = 0;
  }
  GLuint vao_ = 0, vbo_ = 0, ibo_ = 0;
  GLsizei indices_ = 0;
  size_t bytes_ = 0;
};

RL_REGISTER_TECHNIQUE(CellComplexMesh);

}  // namespace rl
