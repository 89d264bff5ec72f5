#include "technique/texture_space_technique.h"

#include <stdexcept>

#include "gpu/scene_uniforms.h"
#include "technique/shader_technique.h"

namespace rl {

ProgramDesc TextureSpaceTechnique::declared_program() const {
  ProgramDesc d = program();
  for (const auto& [name, value] : declared_defines())
    d.defines.emplace(name, value);  // program()'s own define wins on a clash
  return d;
}

void TextureSpaceTechnique::render(const FrameInput& frame, RenderTarget::Kind target) {
  if (const std::string missing = missing_data(frame.map, frame.relief); !missing.empty())
    throw std::logic_error(info().name + " rendered on a scene without " + missing);
  ProgramDesc d = declared_program();
  d.vertex_file = "harness/glsl/texture_space.vert";
  if (target == RenderTarget::Kind::GBuffer) d.defines["RL_GBUFFER"] = "1";
  const GLuint p = ShaderLibrary::shared().program(d);
  glUseProgram(p);
  set_scene_uniforms(p, frame.scene, frame.camera);
  set_frame_uniforms(p, frame);
  frame.relief.bind();
  proxy_.draw_front_faces();
}

std::vector<ProbeHit> TextureSpaceTechnique::probe(const ReliefMap& map, const GpuRelief& relief,
                                                   const std::vector<ProbeRay>& rays, glm::dvec2) {
  if (rays.empty()) return {};
  if (const std::string missing = missing_data(map, relief); !missing.empty())
    throw std::logic_error(info().name + " probed without " + missing);
  ProgramDesc d = declared_program();
  d.vertex_file = "harness/glsl/fullscreen.vert";
  d.defines["RL_PROBE"] = "1";
  const GLuint p = ShaderLibrary::shared().program(d);
  set_probe_uniforms(p, map, relief);
  const GBuffer out = run_probe_pass(p, rays, [&] { relief.bind(); });
  return decode_probe_hits(out, rays.size());
}

}  // namespace rl
