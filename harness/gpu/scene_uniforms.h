#pragma once
// Uniforms every scene pass sets alike: camera, light and the material of shading.glsl.
#include <epoxy/gl.h>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "scene/scene.h"

namespace rl {

inline void set_uniform(GLuint p, const char* name, const glm::dvec3& v) {
  glProgramUniform3f(p, glGetUniformLocation(p, name), float(v.x), float(v.y), float(v.z));
}
inline void set_uniform(GLuint p, const char* name, const glm::dvec2& v) {
  glProgramUniform2f(p, glGetUniformLocation(p, name), float(v.x), float(v.y));
}
inline void set_uniform(GLuint p, const char* name, double v) {
  glProgramUniform1f(p, glGetUniformLocation(p, name), float(v));
}

// rl_view_projection, rl_eye, rl_light and the material (harness/glsl/shading.glsl).
inline void set_scene_uniforms(GLuint p, const SceneDesc& s, const Camera& camera) {
  const glm::mat4 view_proj(camera.projection_matrix() * camera.view_matrix());
  glProgramUniformMatrix4fv(p, glGetUniformLocation(p, "rl_view_projection"), 1, GL_FALSE,
                            glm::value_ptr(view_proj));
  set_uniform(p, "rl_eye", camera.eye);
  set_uniform(p, "rl_light", s.light_position);
  set_uniform(p, "rl_ambient", s.material.ambient);
  set_uniform(p, "rl_diffuse", s.material.diffuse);
  set_uniform(p, "rl_specular", s.material.specular);
  set_uniform(p, "rl_shininess", s.material.shininess);
  set_uniform(p, "rl_shadow_intensity", s.material.shadow_intensity);
}

// For passes that work in the relief's texture space (u, v, depth) rather than on the base:
// rl_world_from_texture (the planar base's map, depth mirrored), rl_normal_from_texture (the
// inverse transpose of its linear part) and rl_eye_texture (the camera in texture space).
inline void set_texture_space_uniforms(GLuint p, const SceneDesc& scene, const Camera& camera) {
  const PlanarBase base = planar_base(scene);
  const glm::dmat4 world_from_texture(glm::dvec4(base.dpdu(), 0), glm::dvec4(base.dpdv(), 0),
                                      glm::dvec4(0, 0, -base.depth, 0),
                                      glm::dvec4(base.world_from_texture({0, 0, 0}), 1));
  const glm::mat4 m(world_from_texture);
  glProgramUniformMatrix4fv(p, glGetUniformLocation(p, "rl_world_from_texture"), 1, GL_FALSE,
                            glm::value_ptr(m));
  const glm::mat3 nm(glm::inverseTranspose(glm::dmat3(world_from_texture)));
  glProgramUniformMatrix3fv(p, glGetUniformLocation(p, "rl_normal_from_texture"), 1, GL_FALSE,
                            glm::value_ptr(nm));
  set_uniform(p, "rl_eye_texture", base.texture_from_world(camera.eye));
}

}  // namespace rl
