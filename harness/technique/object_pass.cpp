#include "technique/object_pass.h"

#include "gl/context.h"
#include "gl/shader_library.h"
#include "technique/scene_uniforms.h"

namespace rl {

ObjectPass::ObjectPass(const std::vector<SceneObject>& objects) {
  const ObjectMesh mesh = make_object_mesh(objects);
  if (mesh.empty()) return;
  GlContext::shared();
  std::vector<glm::vec3> interleaved;
  for (size_t i = 0; i < mesh.position.size(); ++i)
    interleaved.insert(interleaved.end(), {mesh.position[i], mesh.normal[i], mesh.albedo[i]});
  glCreateVertexArrays(1, &vao_);
  glCreateBuffers(1, &vbo_);
  glCreateBuffers(1, &ibo_);
  glNamedBufferStorage(vbo_, interleaved.size() * sizeof(glm::vec3), interleaved.data(), 0);
  glNamedBufferStorage(ibo_, mesh.triangles.size() * sizeof(glm::uvec3), mesh.triangles.data(), 0);
  glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, 3 * sizeof(glm::vec3));
  glVertexArrayElementBuffer(vao_, ibo_);
  for (GLuint a = 0; a < 3; ++a) {
    glEnableVertexArrayAttrib(vao_, a);
    glVertexArrayAttribFormat(vao_, a, 3, GL_FLOAT, GL_FALSE, a * sizeof(glm::vec3));
    glVertexArrayAttribBinding(vao_, a, 0);
  }
  index_count_ = GLsizei(3 * mesh.triangles.size());
}

ObjectPass::~ObjectPass() {
  if (!vao_) return;
  glDeleteVertexArrays(1, &vao_);
  glDeleteBuffers(1, &vbo_);
  glDeleteBuffers(1, &ibo_);
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
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
}

}  // namespace rl
