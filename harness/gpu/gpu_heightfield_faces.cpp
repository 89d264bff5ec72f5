#include "gpu/gpu_heightfield_faces.h"

#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "gl/context.h"

namespace rl {
namespace {

GLuint make_array(const HeightfieldFaces& hf, bool color) {
  const int res = hf.resolution(), layers = hf.count();
  const bool quantized = hf.maps[0].quantized;
  GLuint tex = 0;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &tex);
  glTextureStorage3D(tex, 1, quantized ? GL_RGBA8 : GL_RGBA32F, res, res, layers);
  for (int k = 0; k < layers; ++k) {
    const ReliefMap& m = hf.maps[size_t(k)];
    const std::vector<glm::vec4>& texels = color ? m.color : m.relief;
    glTextureSubImage3D(tex, 0, 0, 0, k, res, res, 1, GL_RGBA, GL_FLOAT, texels.data());
  }
  glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return tex;
}

}  // namespace

GpuHeightfieldFaces::GpuHeightfieldFaces(const HeightfieldFaces& faces) {
  GlContext::shared();
  relief_ = make_array(faces, false);
  color_ = make_array(faces, true);
  bytes_ = faces.bytes();
}

GpuHeightfieldFaces::~GpuHeightfieldFaces() {
  glDeleteTextures(1, &relief_);
  glDeleteTextures(1, &color_);
}

void GpuHeightfieldFaces::bind() const {
  glBindTextureUnit(4, relief_);
  glBindTextureUnit(5, color_);
}

void set_heightfield_faces_uniforms(GLuint p, const HeightfieldFaces& faces) {
  glProgramUniform1i(p, glGetUniformLocation(p, "rl_face_count"), faces.count());
  for (int k = 0; k < faces.count(); ++k) {
    const glm::mat3 m(face_from_cube(faces.faces[size_t(k)]));
    const std::string name = "rl_face_from_cube[" + std::to_string(k) + "]";
    glProgramUniformMatrix3fv(p, glGetUniformLocation(p, name.c_str()), 1, GL_FALSE,
                              glm::value_ptr(m));
  }
  glProgramUniform1f(p, glGetUniformLocation(p, "rl_face_texel"), 1.0f / float(faces.resolution()));
  glProgramUniform1f(p, glGetUniformLocation(p, "rl_face_cop"),
                     float(faces.projection.active() ? faces.projection.cop : 0.0));
}

}  // namespace rl
