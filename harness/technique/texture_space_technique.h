#pragma once
// The skeleton of a technique that draws its own proxy in the relief's texture space (a cube,
// or a cell complex's grey cells) and runs one fragment program both for frames and for probe
// rays: the cell-complex ray caster and the several-heightfield object (Baboud & Decoret,
// Section 4.2) differ only in their program, their proxy and the uniforms their data needs.
#include <string>
#include <vector>

#include "gl/shader_library.h"
#include "gpu/texture_space_geometry.h"
#include "technique/technique.h"

namespace rl {

class TextureSpaceTechnique : public Technique {
 public:
  using Technique::Technique;
  // Draws the proxy's front faces with program() (texture-space vertices, G-buffer outputs
  // compiled in for a G-buffer target).
  void render(const FrameInput& frame, RenderTarget::Kind target) override;
  // Runs program() on a full-screen pass of rays (texture-space origin and direction, any
  // direction; t counts multiples of the direction).
  std::vector<ProbeHit> probe(const ReliefMap& map, const GpuRelief& relief,
                              const std::vector<ProbeRay>& rays, glm::dvec2) override;

 protected:
  // The fragment files and parameter defines (no vertex file: render and probe choose it).
  virtual ProgramDesc program() const = 0;
  // program() with the declared parameters' defines (ParamSpec::define) added.
  ProgramDesc declared_program() const;
  // What the map and its GPU copy must hold ("" when they do, else what is missing).
  virtual std::string missing_data(const ReliefMap& map, const GpuRelief& relief) const = 0;
  // Uniforms of a frame beyond the scene's (set_scene_uniforms is already done).
  virtual void set_frame_uniforms(GLuint program, const FrameInput& frame) const = 0;
  // Uniforms of a probe pass.
  virtual void set_probe_uniforms(GLuint program, const ReliefMap& map,
                                  const GpuRelief& relief) const = 0;

  PositionBuffer proxy_;  // set by prepare()
};

}  // namespace rl
