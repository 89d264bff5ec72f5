// The relief as triangles, rasterised: Baboud & Decoret's point of comparison (Table 1's mesh
// column; Section 5's "a 256 x 256 texture ... would equal a 64K mesh"). The bilinear surface
// the other techniques search, cut at every texel-centre line into cells of `subdivision` ^ 2
// quads, two triangles each; no texture fetch per pixel.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "gl/shader_library.h"
#include "gpu/scene_uniforms.h"
#include "gpu/triangle_buffers.h"
#include "relief/relief_map.h"
#include "scene/scene.h"
#include "technique/technique.h"

namespace rl {
namespace {

constexpr double kMaxTriangles = 32e6;  // about 1 GB of vertex and index data beyond this

// The grid lines across [0, tile] of one axis: texel-centre lines of a map `texels` wide and the
// two borders, each interval between them cut into `sub` equal parts.
std::vector<double> grid_lines(int texels, double tile, int sub) {
  std::vector<double> knots = {0.0};
  for (long i = 0; (i + 0.5) / texels < tile; ++i) knots.push_back((i + 0.5) / texels);
  knots.push_back(tile);
  std::vector<double> lines;
  for (size_t k = 0; k + 1 < knots.size(); ++k)
    for (int s = 0; s < sub; ++s) lines.push_back(knots[k] + (knots[k + 1] - knots[k]) * s / sub);
  lines.push_back(tile);
  return lines;
}

// The map's tangent-space normal at (u, v) (x along u, y along v, z out) in texture space (u, v,
// depth down), which the shader's inverse-transpose map takes back to the world: shaded as every
// other technique and the truth shade.
glm::vec3 shading_normal(const ReliefMap& map, const PlanarBase& base, double u, double v) {
  const glm::dvec3 t = decode_normal(map.sample_relief(u, v));
  return glm::vec3(t.x * glm::length(base.dpdu()), t.y * glm::length(base.dpdv()),
                   -t.z * base.depth);
}

class HeightfieldMesh final : public Described<HeightfieldMesh, Technique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {
        .name = "heightfield_mesh",
        .title = "The relief as triangles, rasterised (baseline)",
        .citation = "Baboud & Decoret 2006, Table 1 (the mesh column) and Section 5",
        .effects = {Effect::DepthCorrect},
        .params = {{.name = "subdivision",
                    .kind = ParamKind::Int,
                    .default_value = 1,
                    .min_value = 1,
                    .max_value = 8,
                    .doc = "quads per side of each bilinear cell (two triangles each): the mesh "
                           "approaches the bilinear surface as it grows"}},
        .draws = {.reads = {Representation::Heightfield},
                  .bases = {BaseShape::Planar},
                  .proxies = {Proxy::Box},
                  .projections = {Projection::Plain}},
        .contract = {.answer = Answer::Converging,
                     .max_fetches = [](const RayQuery&) { return 0; },
                     .max_fetches_formula = "0: rasterised triangles",
                     .knobs = {{"subdivision"}},
                     .finest = {{"subdivision", 8}},
                     .accuracy = "the bilinear surface as 2 subdivision^2 triangles per texel "
                                 "cell: exact at the cells' corners, off by up to a quarter of a "
                                 "cell's twist between them (at subdivision 1)",
                     .ray_probe = false,
                     .hits_from_inside = false}};
  }
  void prepare_scene(const SceneDesc& scene, const ReliefMap& map) override {
    const int sub = subdivision_;
    const std::vector<double> us = grid_lines(map.width, scene.tile, sub),
                              vs = grid_lines(map.height, scene.tile, sub);
    const double triangles = 2.0 * double(us.size() - 1) * double(vs.size() - 1);
    if (triangles > kMaxTriangles)
      throw std::runtime_error("heightfield_mesh: " + std::to_string(long(triangles)) +
                               " triangles for scene '" + scene.name +
                               "' (tile x map x subdivision); at most " +
                               std::to_string(long(kMaxTriangles)));
    std::vector<glm::vec3> position, normal, color;
    const PlanarBase base = planar_base(scene);
    for (double v : vs)
      for (double u : us) {
        position.emplace_back(u, v, map.sample_depth(u, v));
        normal.push_back(shading_normal(map, base, u, v));
        color.emplace_back(glm::dvec3(map.sample_color(u, v)));
      }
    std::vector<glm::uvec3> tris;
    const unsigned row = unsigned(us.size());
    for (unsigned j = 0; j + 1 < vs.size(); ++j)
      for (unsigned i = 0; i + 1 < row; ++i) {
        const unsigned a = j * row + i, b = a + 1, c = a + row, d = c + 1;
        // An empty floor (an object baked in its box) is no surface: triangles lying on it go.
        auto on_floor = [&](unsigned x, unsigned y, unsigned z) {
          return scene.empty_floor && position[x].z >= 1.0f && position[y].z >= 1.0f &&
                 position[z].z >= 1.0f;
        };
        if (!on_floor(a, b, d)) tris.push_back({a, b, d});
        if (!on_floor(a, d, c)) tris.push_back({a, d, c});
      }
    add_skirt(map, base, us, vs, position, normal, color, tris);
    buffers_ = TriangleBuffers(position, normal, color, tris);
  }

  // The box's four sides, from the surface down to depth 1: the relief as the closed solid in
  // its box that the box proxy's truth traces, seen through the sides at grazing views. Shaded
  // like the others shade a hit there: with the map's normal at that (u, v).
  static void add_skirt(const ReliefMap& map, const PlanarBase& base, const std::vector<double>& us,
                        const std::vector<double>& vs, std::vector<glm::vec3>& position,
                        std::vector<glm::vec3>& normal, std::vector<glm::vec3>& color,
                        std::vector<glm::uvec3>& tris) {
    auto side = [&](const std::vector<glm::dvec2>& edge) {
      const unsigned first = unsigned(position.size());
      for (const glm::dvec2& e : edge)
        for (double d : {map.sample_depth(e.x, e.y), 1.0}) {
          position.emplace_back(e.x, e.y, d);
          normal.push_back(shading_normal(map, base, e.x, e.y));
          color.emplace_back(glm::dvec3(map.sample_color(e.x, e.y)));
        }
      for (unsigned k = 0; k + 1 < edge.size(); ++k) {
        const unsigned a = first + 2 * k, b = a + 2;  // top of this and the next; +1: bottom
        tris.push_back({a, b, b + 1});
        tris.push_back({a, b + 1, a + 1});
      }
    };
    std::vector<glm::dvec2> south, north, west, east;
    for (double u : us) {
      south.emplace_back(u, vs.front());
      north.emplace_back(u, vs.back());
    }
    for (double v : vs) {
      west.emplace_back(us.front(), v);
      east.emplace_back(us.back(), v);
    }
    for (const std::vector<glm::dvec2>* edge : {&south, &north, &west, &east}) side(*edge);
  }

  void render(const FrameInput& frame, RenderTarget::Kind target) override {
    if (buffers_.empty()) prepare_scene(frame.scene, frame.map);
    ProgramDesc d;
    d.owner = info().name;
    // The cell-complex geometry renderer's shaders: triangles in texture space, per-vertex
    // normals and colours, no fetch.
    d.vertex_file = "techniques/cell_complex_mesh/cell_mesh_vert.glsl";
    d.fragment_files = {"techniques/cell_complex_mesh/cell_mesh_frag.glsl"};
    d.defines["RL_NORMALS_AS_GIVEN"] = "1";
    if (target == RenderTarget::Kind::GBuffer) d.defines["RL_GBUFFER"] = "1";
    const GLuint p = ShaderLibrary::shared().program(d);
    glUseProgram(p);
    set_scene_uniforms(p, frame.scene, frame.camera);
    set_texture_space_uniforms(p, frame.scene, frame.camera);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    buffers_.draw();
  }

  std::vector<ProbeHit> probe(const ReliefMap&, const GpuRelief&, const std::vector<ProbeRay>&,
                              glm::dvec2) override {
    throw std::logic_error("heightfield_mesh rasterises its surface; it has no ray search");
  }

  size_t memory_bytes() const override { return buffers_.bytes(); }

 private:
  const int subdivision_ = param<int>("subdivision");
  TriangleBuffers buffers_;
};

}  // namespace

RL_REGISTER_TECHNIQUE(HeightfieldMesh);

}  // namespace rl
