#include "gpu/gpu_scene.h"

#include <cstddef>
#include <vector>

#include "gl/context.h"
#include "relief/meta_relief.h"

namespace rl {

GLuint make_texture(int w, int h, GLenum internal_format, GLenum format, const float* texels) {
  GLuint tex = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &tex);
  glTextureStorage2D(tex, 1, internal_format, w, h);
  glTextureSubImage2D(tex, 0, 0, 0, w, h, format, GL_FLOAT, texels);
  // Bilinear, repeating, no mipmaps: the exact surface the truth reconstructs.
  glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return tex;
}

GpuRelief::GpuRelief(const ReliefMap& map, bool meta_layers) {
  GlContext::shared();
  const GLenum rgba = map.quantized ? GL_RGBA8 : GL_RGBA32F;
  relief_ = make_texture(map.width, map.height, rgba, GL_RGBA,
                         reinterpret_cast<const float*>(map.relief.data()));
  color_ = make_texture(map.color_w(), map.color_h(), rgba, GL_RGBA,
                        reinterpret_cast<const float*>(map.color.data()));
  if (!map.ambient_visibility.empty())
    ambient_ = make_texture(map.width, map.height, map.quantized ? GL_R8 : GL_R32F, GL_RED,
                            map.ambient_visibility.data());
  if (meta_layers && map.meta)
    for (const MetaLayer& layer : map.meta->layers())
      meta_layers_.push_back(make_texture(layer.map.width, layer.map.height, rgba, GL_RGBA,
                                          reinterpret_cast<const float*>(layer.map.relief.data())));
  if (meta_layers && map.meta)
    for (size_t i = 0; i < map.meta_ambient_visibility.size(); ++i) {
      const ReliefMap& layer = map.meta->layers()[i].map;
      meta_ambient_.push_back(make_texture(layer.width, layer.height,
                                           map.quantized ? GL_R8 : GL_R32F, GL_RED,
                                           map.meta_ambient_visibility[i].data()));
    }
  bytes_ = map.gpu_bytes(!meta_layers_.empty());
  if (map.cells) {
    // The complex is the representation: its flat placeholder map counts for nothing.
    cells_ = std::make_unique<GpuCellComplex>(*map.cells);
    bytes_ = cells_->bytes();
  }
  if (map.faces) {
    // Every face is the representation (the top face's map is one of them).
    faces_ = std::make_unique<GpuHeightfieldFaces>(*map.faces);
    bytes_ = faces_->bytes();
  }
}

GpuRelief::~GpuRelief() {
  glDeleteTextures(1, &relief_);
  glDeleteTextures(1, &color_);
  if (ambient_) glDeleteTextures(1, &ambient_);
  if (!meta_layers_.empty()) glDeleteTextures(GLsizei(meta_layers_.size()), meta_layers_.data());
  if (!meta_ambient_.empty()) glDeleteTextures(GLsizei(meta_ambient_.size()), meta_ambient_.data());
}

void GpuRelief::bind(GLuint relief_unit, GLuint color_unit) const {
  glBindTextureUnit(relief_unit, relief_);
  glBindTextureUnit(color_unit, color_);
  if (ambient_) glBindTextureUnit(8, ambient_);
  for (size_t i = 0; i < meta_layers_.size(); ++i)
    glBindTextureUnit(GLuint(10 + i), meta_layers_[i]);
  for (size_t i = 0; i < meta_ambient_.size(); ++i)
    glBindTextureUnit(GLuint(18 + i), meta_ambient_[i]);
  if (cells_) cells_->bind();
  if (faces_) faces_->bind();
}

GpuBase::GpuBase(const BaseGeometry& g) {
  GlContext::shared();
  glCreateVertexArrays(1, &vao_);
  glCreateBuffers(1, &vbo_);
  glCreateBuffers(1, &ibo_);
  glNamedBufferStorage(vbo_, g.vertices.size() * sizeof(BaseVertex), g.vertices.data(), 0);
  glNamedBufferStorage(ibo_, g.indices.size() * sizeof(unsigned), g.indices.data(), 0);
  glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, sizeof(BaseVertex));
  glVertexArrayElementBuffer(vao_, ibo_);
  const struct {
    GLuint location;
    GLint size;
    size_t offset;
  } attributes[] = {
      {0, 3, offsetof(BaseVertex, position)}, {1, 2, offsetof(BaseVertex, uv)},
      {2, 3, offsetof(BaseVertex, dpdu)},     {3, 3, offsetof(BaseVertex, dpdv)},
      {4, 3, offsetof(BaseVertex, normal)},   {5, 1, offsetof(BaseVertex, entry_depth)},
      {6, 2, offsetof(BaseVertex, curvature)}};
  for (const auto& a : attributes) {
    glEnableVertexArrayAttrib(vao_, a.location);
    glVertexArrayAttribFormat(vao_, a.location, a.size, GL_FLOAT, GL_FALSE,
                              static_cast<GLuint>(a.offset));
    glVertexArrayAttribBinding(vao_, a.location, 0);
  }
  index_count_ = static_cast<GLsizei>(g.indices.size());
}

GpuBase::~GpuBase() {
  glDeleteVertexArrays(1, &vao_);
  glDeleteBuffers(1, &vbo_);
  glDeleteBuffers(1, &ibo_);
}

void GpuBase::draw() const {
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
}

}  // namespace rl
