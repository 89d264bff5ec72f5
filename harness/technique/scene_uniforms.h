#pragma once
// Uniforms every scene pass sets alike: camera, light and the material of shading.glsl.
#include <epoxy/gl.h>
#include <glm/glm.hpp>
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

}  // namespace rl
