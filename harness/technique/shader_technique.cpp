#include "technique/shader_technique.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "gl/render_target.h"
#include "gpu/scene_uniforms.h"
#include "relief/meta_relief.h"

namespace rl {

Defines layered_floor_define(const ReliefMap& map) {
  if (map.layers.empty()) return {};
  const glm::vec3 c = map.floor_color;
  return {{"RL_LAYERED_FLOOR", "vec3(" + std::to_string(c.r) + ", " + std::to_string(c.g) + ", " +
                                   std::to_string(c.b) + ")"}};
}

void set_meta_relief_uniforms(GLuint program, const ReliefMap& map) {
  if (!map.meta) throw std::logic_error("a meta-relief variant without the map's layers");
  std::vector<float> tiling, normal_share, depth_share;
  for (size_t i = 0; i < map.meta->layers().size(); ++i) {
    tiling.push_back(float(map.meta->layers()[i].tiling));
    normal_share.push_back(float(map.meta->normal_share(i)));
    depth_share.push_back(float(map.meta->depth_share(i)));
  }
  const GLsizei n = GLsizei(tiling.size());
  glProgramUniform1fv(program, glGetUniformLocation(program, "rl_meta_tiling"), n, tiling.data());
  glProgramUniform1fv(program, glGetUniformLocation(program, "rl_meta_normal_share"), n,
                      normal_share.data());
  glProgramUniform1fv(program, glGetUniformLocation(program, "rl_meta_depth_share"), n,
                      depth_share.data());
}

SurfaceVariant ShaderTechnique::variant_of(const SceneDesc& scene) {
  return {scene.proxy, scene.empty_floor, scene.projection.active(), scene.impostor(),
          // Through a pattern's gaps on a closed base the far side shows, unless a solid floor
          // (the underlying model) fills it.
          scene.base.curved() && scene.relief.layers > 0 && scene.empty_floor,
          scene.drawn_effects().has(Effect::AmbientOcclusion) &&
              scene.ao.update == AmbientOcclusionDesc::Update::Eq6 &&
              scene.ao.rescale(scene.depth) != 1.0,
          scene.meta.runtime() ? 1 + int(scene.meta.layers.size()) : 0,
          scene.meta.runtime() ? scene.meta.ao_combine : MetaReliefDesc::AoCombine::Bake, false,
          scene.effects.has(Effect::SceneShadows) && !scene.shadow_map.corrected_depth};
}

bool ShaderTechnique::draws_back_faces(const SurfaceVariant& variant) const {
  // Only a technique that searches upward too draws back faces; the others keep their
  // one-sided search (and miss the far side through the gaps, as a heightfield would).
  return variant.two_sided && info().draws.reads.has(Representation::Impostor);
}

Defines ShaderTechnique::all_parameter_defines() const {
  Defines d = declared_defines();
  for (const auto& [name, value] : parameter_defines()) d[name] = value;
  return d;
}

ProgramDesc ShaderTechnique::surface_program(EffectSet effects, RenderTarget::Kind target,
                                             SurfaceVariant variant) const {
  ProgramDesc d;
  d.owner = info().name;
  d.vertex_file = "harness/glsl/base.vert";
  d.fragment_files = {intersect_file(), "harness/glsl/surface_main.glsl"};
  d.defines = all_parameter_defines();
  for (Effect e : effects.list()) d.defines[effect_define(e)] = "1";
  if (target == RenderTarget::Kind::GBuffer) d.defines["RL_GBUFFER"] = "1";
  if (variant.proxy == Proxy::Box) d.defines["RL_PROXY_BOX"] = "1";
  if (variant.empty_floor) d.defines["RL_EMPTY_FLOOR"] = "1";
  if (variant.reverse_perspective) d.defines["RL_REVERSE_PERSPECTIVE"] = "1";
  if (variant.impostor) d.defines["RL_IMPOSTOR"] = "1";
  if (draws_back_faces(variant)) d.defines["RL_TWO_SIDED"] = "1";
  if (variant.ao_eq6 && effects.has(Effect::AmbientOcclusion)) d.defines["RL_AO_EQ6"] = "1";
  if (variant.meta_layers > 0) d.defines["RL_META_LAYERS"] = std::to_string(variant.meta_layers);
  if (variant.shadow_caster) d.defines["RL_SHADOW_CASTER"] = "1";
  if (variant.shadow_at_base && effects.has(Effect::SceneShadows))
    d.defines["RL_SHADOW_AT_BASE"] = "1";
  if (variant.meta_layers > 0 && effects.has(Effect::AmbientOcclusion)) {
    if (variant.meta_ao == MetaReliefDesc::AoCombine::Product)
      d.defines["RL_META_AO_PRODUCT"] = "1";
    if (variant.meta_ao == MetaReliefDesc::AoCombine::Min) d.defines["RL_META_AO_MIN"] = "1";
  }
  return d;
}

ProgramDesc ShaderTechnique::probe_program() const {
  ProgramDesc d;
  d.owner = info().name;
  d.vertex_file = "harness/glsl/fullscreen.vert";
  d.fragment_files = {intersect_file(), "harness/glsl/probe_main.glsl"};
  d.defines = all_parameter_defines();
  d.defines["RL_PROBE"] = "1";
  return d;
}

void ShaderTechnique::render(const FrameInput& frame, RenderTarget::Kind target) {
  const SceneDesc& s = frame.scene;
  SurfaceVariant variant = variant_of(s);
  variant.shadow_caster = frame.shadow_caster;
  const bool receives = frame.effects.has(Effect::SceneShadows) && !frame.shadow_caster;
  if (receives && !frame.shadow_map)
    throw std::logic_error("scene '" + s.name + "' asks for scene_shadows, but the frame of " +
                           info().name + " has no shadow map");
  const GLuint p = ShaderLibrary::shared().program(surface_program(frame.effects, target, variant));
  glUseProgram(p);
  set_scene_uniforms(p, s, frame.camera);
  if (receives) frame.shadow_map->bind(p);
  const PlanarBase base = planar_base(s);
  glProgramUniform2f(p, glGetUniformLocation(p, "rl_uv_max"), float(s.tile), float(s.tile));
  set_uniform(p, "rl_eye_affine", base.texture_from_world(frame.camera.eye));
  set_uniform(p, "rl_cop", s.projection.cop);
  set_uniform(p, "rl_depth_scale", s.depth);
  set_uniform(p, "rl_shadow_bias", s.shadow_bias);
  set_uniform(p, "rl_ao_rescale", s.ao.rescale(s.depth));
  if (variant_of(s).meta_layers > 0) set_meta_relief_uniforms(p, frame.map);
  frame.relief.bind();
  bind_resources(p);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  // A box proxy is drawn front faces only: each pixel's ray enters the box once.
  if (s.proxy == Proxy::Box) {
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
  } else {
    glDisable(GL_CULL_FACE);
  }
  if (draws_back_faces(variant_of(s)) && two_pass()) {
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    frame.base.draw();
    glCullFace(GL_FRONT);
  }
  frame.base.draw();
  glDisable(GL_CULL_FACE);
}

GBuffer run_probe_pass(GLuint program, const std::vector<ProbeRay>& rays,
                       const std::function<void()>& bind) {
  // Rays are laid out in rows of up to 1024 texels; one fragment traces one ray.
  const int width = static_cast<int>(std::min<size_t>(rays.size(), 1024));
  const int height = static_cast<int>((rays.size() + width - 1) / width);
  std::vector<glm::vec4> origins(static_cast<size_t>(width) * height, glm::vec4(0, 0, 0, 0));
  std::vector<glm::vec4> directions(origins.size(), glm::vec4(0, 0, 1, 0));
  for (size_t i = 0; i < rays.size(); ++i) {
    origins[i] = glm::vec4(rays[i].origin, rays[i].quadric.x);
    directions[i] = glm::vec4(rays[i].direction, rays[i].quadric.y);
  }
  GLuint inputs[2];
  glCreateTextures(GL_TEXTURE_2D, 2, inputs);
  const std::vector<glm::vec4>* data[2] = {&origins, &directions};
  for (int i = 0; i < 2; ++i) {
    glTextureStorage2D(inputs[i], 1, GL_RGBA32F, width, height);
    glTextureSubImage2D(inputs[i], 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, data[i]->data());
    glTextureParameteri(inputs[i], GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(inputs[i], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  RenderTarget target(width, height, RenderTarget::Kind::GBuffer);
  target.bind_and_clear();
  glUseProgram(program);
  bind();
  glBindTextureUnit(2, inputs[0]);
  glBindTextureUnit(3, inputs[1]);
  glDisable(GL_DEPTH_TEST);
  GLuint vao;
  glCreateVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  GBuffer out;
  target.read_back(out);
  glDeleteVertexArrays(1, &vao);
  glDeleteTextures(2, inputs);
  return out;
}

std::vector<ProbeHit> ShaderTechnique::probe(const ReliefMap& map, const GpuRelief& relief,
                                             const std::vector<ProbeRay>& rays,
                                             glm::dvec2 depth_aspect) {
  (void)map;
  if (rays.empty()) return {};
  const GLuint p = ShaderLibrary::shared().program(probe_program());
  set_uniform(p, "rl_probe_depth_aspect", depth_aspect);
  const GBuffer out = run_probe_pass(p, rays, [&] {
    relief.bind();
    bind_resources(p);
  });
  return decode_probe_hits(out, rays.size());
}

std::vector<ProbeHit> decode_probe_hits(const GBuffer& out, size_t count) {
  std::vector<ProbeHit> hits(count);
  for (size_t i = 0; i < count; ++i) {
    const glm::vec4 a = out.color[i], b = out.position[i];
    hits[i].t = a.x;
    hits[i].uv = glm::vec2(a.y, a.z);
    hits[i].fetches = static_cast<int>(a.w);
    hits[i].depth = b.x;
    hits[i].layer = static_cast<int>(b.y);
    hits[i].hit = b.z > 0.5f;
  }
  return hits;
}

}  // namespace rl
