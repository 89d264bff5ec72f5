#include "technique/object_pass.h"

#include "gl/context.h"
#include "gl/shader_library.h"
#include "gpu/scene_uniforms.h"

namespace rl {

ObjectPass::ObjectPass(const std::vector<SceneObject>& objects) {
  const ObjectMesh mesh = make_object_mesh(objects);
  buffers_ = TriangleBuffers(mesh.position, mesh.normal, mesh.albedo, mesh.triangles);
}

void ObjectPass::draw(const SceneDesc& scene, const Camera& camera,
                      RenderTarget::Kind target) const {
  if (empty()) return;
  ProgramDesc d;
  d.owner = "objects";
  d.vertex_file = "harness/glsl/object.vert";
  d.fragment_files = {"harness/glsl/object.frag"};
  if (target == RenderTarget::Kind::GBuffer) d.defines["RL_GBUFFER"] = "1";
  const GLuint p = ShaderLibrary::shared().program(d);
  glUseProgram(p);
  set_scene_uniforms(p, scene, camera);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  // Both sides, as the truth traces them: a mesh file's winding is not known.
  glDisable(GL_CULL_FACE);
  buffers_.draw();
}

}  // namespace rl
