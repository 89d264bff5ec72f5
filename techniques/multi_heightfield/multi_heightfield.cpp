// Objects from several heightfields, ray cast (Baboud & Decoret 2006, Section 4.2).
#include <stdexcept>

#include "gpu/gpu_heightfield_faces.h"
#include "gpu/scene_uniforms.h"
#include "relief/heightfield_faces.h"
#include "technique/texture_space_technique.h"

namespace rl {

class MultiHeightfield final : public Described<MultiHeightfield, TextureSpaceTechnique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {.name = "multi_heightfield",
            .title = "Object from several heightfields (linear + binary search)",
            .citation =
                "Baboud & Decoret, 'Rendering geometry with relief textures', "
                "Section 4.2 (and Oliveira et al.'s six relief textures on a box)",
            .effects = {Effect::DepthCorrect},
            .params = {linear_steps_param(
                           64,
                           "linear search samples along the ray's chord through the cube; "
                           "each asks the faces in turn until one says outside"),
                       binary_steps_param(6, "binary search refinements after the linear search")},
            .draws = {.reads = {Representation::HeightfieldObject},
                      .proxies = {Proxy::Base, Proxy::Box}},
            .contract = {
                .answer = Answer::Converging,
                .max_fetches =
                    [](const RayQuery& q) {
                      return q.faces * (q.param("linear_steps") + 1 + q.param("binary_steps")) + 2;
                    },
                .max_fetches_formula = "faces x (linear_steps + 1 + binary_steps), + 2 to shade",
                .knobs = {{"linear_steps"}, {"binary_steps"}},
                .finest = {{"linear_steps", 1024}, {"binary_steps", 16}},
                .accuracy = "the first entry into every face's solid to within one linear step "
                            "(of the cube's diagonal) / 2^binary_steps along the ray"}};
  }

  void prepare(const ReliefMap& map) override {
    if (!map.faces) throw std::logic_error("multi_heightfield prepared without heightfield faces");
    std::vector<glm::vec3> tris;
    for (int f = 0; f < kCubeFaces; ++f) append_cube_face(tris, {0, 0, 0}, f, 1);
    proxy_.set(tris);
  }

 protected:
  std::string missing_data(const ReliefMap& map, const GpuRelief& relief) const override {
    return map.faces && relief.faces() ? "" : "heightfield faces";
  }
  void set_frame_uniforms(GLuint p, const FrameInput& frame) const override {
    set_texture_space_uniforms(p, frame.scene, frame.camera);
    set_heightfield_faces_uniforms(p, *frame.map.faces);
  }
  // Probe rays are in the cube's texture space, any direction, starting inside the cube; t
  // counts multiples of the direction. The search runs to the ray's exit from the cube.
  void set_probe_uniforms(GLuint p, const ReliefMap& map, const GpuRelief&) const override {
    set_heightfield_faces_uniforms(p, *map.faces);
  }
  ProgramDesc program() const override {
    ProgramDesc d;
    d.owner = info().name;
    d.fragment_files = {"techniques/multi_heightfield/multi_heightfield.glsl"};
    return d;
  }
};

RL_REGISTER_TECHNIQUE(MultiHeightfield);

}  // namespace rl
