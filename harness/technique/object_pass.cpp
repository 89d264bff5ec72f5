#include "technique/object_pass.h"

#include "gl/context.h"
#include "gl/shader_library.h"
#include "gpu/scene_uniforms.h"
#include "technique/shadow_map_pass.h"

namespace rl {

ObjectPass::ObjectPass(const std::vector<SceneObject>& objects) {
  const ObjectMesh mesh = make_object_mesh(objects);
  buffers_ = TriangleBuffers(mesh.position, mesh.normal, mesh.albedo, mesh.triangles);
}

namespace {

ProgramDesc object_program() {
  ProgramDesc d;
  d.owner = "objects";
  d.vertex_file = "harness/glsl/object.vert";
  d.fragment_files = {"harness/glsl/object.frag"};
  return d;
}

}  // namespace

void ObjectPass::draw(const SceneDesc& scene, const Camera& camera, RenderTarget::Kind target,
                      const ShadowMapPass* shadows) const {
  ProgramDesc d = object_program();
  if (target == RenderTarget::Kind::GBuffer) d.defines["RL_GBUFFER"] = "1";
  if (shadows) d.defines[effect_define(Effect::SceneShadows)] = "1";
  draw_with(d, scene, camera, shadows);
}

void ObjectPass::draw_caster(const SceneDesc& scene, const Camera& light) const {
  ProgramDesc d = object_program();
  d.defines["RL_SHADOW_CASTER"] = "1";
  draw_with(d, scene, light, nullptr);
}

void ObjectPass::draw_with(const ProgramDesc& program, const SceneDesc& scene, const Camera& camera,
                           const ShadowMapPass* shadows) const {
  if (empty()) return;
  const GLuint p = ShaderLibrary::shared().program(program);
  glUseProgram(p);
  set_scene_uniforms(p, scene, camera);
  if (shadows) shadows->bind(p);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  // Both sides, as the truth traces them: a mesh file's winding is not known.
  glDisable(GL_CULL_FACE);
  buffers_.draw();
}

}  // namespace rl
