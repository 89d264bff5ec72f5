#pragma once
// Base for techniques that are one GLSL intersection routine, `RlHit rl_intersect(vec3 p,
// vec3 s)`, run per fragment of the base surface. The harness owns the passes around it:
// harness/glsl/surface_main.glsl (view ray, shading, self-shadow ray, G-buffer outputs) and
// harness/glsl/probe_main.glsl (ray-probe mode), so every such technique is measured alike.
#include <functional>
#include <string>
#include <vector>

#include "core/gbuffer.h"
#include "gl/shader_library.h"
#include "technique/technique.h"

namespace rl {

// The #define a technique on a multilayer map adds so its misses shade like the truth's solid
// floor (map.floor_color, facing up); empty for heightfield maps.
Defines layered_floor_define(const ReliefMap& map);
// The tilings and weight shares of a meta-relief combined per fetch (RL_META_LAYERS).
void set_meta_relief_uniforms(GLuint program, const ReliefMap& map);

// Runs `program`, a probe pass, once per ray: origins (xyz, quadric.x) on unit 2 and
// directions (xyz, quadric.y) on unit 3, one fragment per ray in rows of up to 1024, after
// `bind` has bound its textures; returns the pass's G-buffer (ray i at texel i).
GBuffer run_probe_pass(GLuint program, const std::vector<ProbeRay>& rays,
                       const std::function<void()>& bind);
// The hits of `count` rays from a probe pass's G-buffer, as harness/glsl/probe_io.glsl writes
// them: (t, u, v, fetches) in colour, (depth, layer, hit) in position.
std::vector<ProbeHit> decode_probe_hits(const GBuffer& out, size_t count);

// How a scene's relief is drawn, as far as the surface shader is concerned.
struct SurfaceVariant {
  Proxy proxy = Proxy::Base;
  bool empty_floor = false;
  bool reverse_perspective = false;
  bool impostor = false;
  bool two_sided = false;  // a pattern on a closed curved base: back faces show through gaps
  bool ao_eq6 = false;     // ambient_occlusion on a rescaled relief, updated by Eq. 6
  int meta_layers = 0;     // a meta-relief combined per fetch: its layer count (RL_META_LAYERS)
  // ... with ambient_occlusion from its layers' AO maps combined per fetch (not from the bake's)
  MetaReliefDesc::AoCombine meta_ao = MetaReliefDesc::AoCombine::Bake;
  bool shadow_caster = false;  // drawn into scene_shadows' shadow map: depth only
  // scene_shadows with shadow_map.depth = "base": the relief casts and receives at its base
  // surface, as an undisplaced surface would.
  bool shadow_at_base = false;
};

class ShaderTechnique : public Technique {
 public:
  using Technique::Technique;

  void render(const FrameInput& frame, RenderTarget::Kind target) override;
  std::vector<ProbeHit> probe(const ReliefMap& map, const GpuRelief& relief,
                              const std::vector<ProbeRay>& rays, glm::dvec2 depth_aspect) override;

  // The program a render with these effects and this target uses (tests inspect its source).
  static SurfaceVariant variant_of(const SceneDesc& scene);
  ProgramDesc surface_program(EffectSet effects, RenderTarget::Kind target,
                              SurfaceVariant variant = {}) const;
  ProgramDesc probe_program() const;

 protected:
  // GLSL file defining rl_intersect, e.g. "techniques/relief/relief.glsl".
  virtual std::string intersect_file() const = 0;
  // #defines beyond those the declared parameters set themselves (ParamSpec::define): ones that
  // depend on the map or combine parameters, e.g. {"RL_LAYER_GROUPS", "2"}.
  virtual Defines parameter_defines() const { return {}; }
  // The declared parameters' defines, then parameter_defines() (which wins on a clash).
  Defines all_parameter_defines() const;
  // Binds the technique's own textures (precomputed maps) for a draw with `program`; units
  // 0-3 and 8 are the harness's (relief, colour, probe rays; the AO map).
  virtual void bind_resources(GLuint program) const { (void)program; }
  // Two-sided variants only: draw front faces, then back faces (Policarpo & Oliveira 2006,
  // Section 5: back faces behind a found hit are then rejected by the depth test), instead of
  // all faces in the mesh's order.
  virtual bool two_pass() const { return false; }

 private:
  bool draws_back_faces(const SurfaceVariant& variant) const;
};

}  // namespace rl
