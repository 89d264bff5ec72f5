#include "gpu/triangle_buffers.h"

#include <algorithm>
#include <utility>

#include "gl/context.h"

namespace rl {

TriangleBuffers::TriangleBuffers(const std::vector<glm::vec3>& position,
                                 const std::vector<glm::vec3>& normal,
                                 const std::vector<glm::vec3>& color,
                                 const std::vector<glm::uvec3>& triangles) {
  if (triangles.empty()) return;
  GlContext::shared();
  std::vector<glm::vec3> interleaved;
  interleaved.reserve(3 * position.size());
  for (size_t i = 0; i < position.size(); ++i)
    interleaved.insert(interleaved.end(), {position[i], normal[i], color[i]});
  glCreateVertexArrays(1, &vao_);
  glCreateBuffers(1, &vbo_);
  glCreateBuffers(1, &ibo_);
  glNamedBufferStorage(vbo_, GLsizeiptr(interleaved.size() * sizeof(glm::vec3)), interleaved.data(),
                       0);
  glNamedBufferStorage(ibo_, GLsizeiptr(triangles.size() * sizeof(glm::uvec3)), triangles.data(),
                       0);
  glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, 3 * sizeof(glm::vec3));
  glVertexArrayElementBuffer(vao_, ibo_);
  for (GLuint a = 0; a < 3; ++a) {
    glEnableVertexArrayAttrib(vao_, a);
    glVertexArrayAttribFormat(vao_, a, 3, GL_FLOAT, GL_FALSE, a * sizeof(glm::vec3));
    glVertexArrayAttribBinding(vao_, a, 0);
  }
  index_count_ = GLsizei(3 * triangles.size());
  bytes_ = interleaved.size() * sizeof(glm::vec3) + triangles.size() * sizeof(glm::uvec3);
}

TriangleBuffers::~TriangleBuffers() {
  release();
}

TriangleBuffers::TriangleBuffers(TriangleBuffers&& other) noexcept {
  *this = std::move(other);
}

TriangleBuffers& TriangleBuffers::operator=(TriangleBuffers&& other) noexcept {
  if (this != &other) {
    release();
    std::swap(vao_, other.vao_);
    std::swap(vbo_, other.vbo_);
    std::swap(ibo_, other.ibo_);
    std::swap(index_count_, other.index_count_);
    std::swap(bytes_, other.bytes_);
  }
  return *this;
}

void TriangleBuffers::release() {
  if (vao_) glDeleteVertexArrays(1, &vao_);
  if (vbo_) glDeleteBuffers(1, &vbo_);
  if (ibo_) glDeleteBuffers(1, &ibo_);
  vao_ = vbo_ = ibo_ = 0;
  index_count_ = 0;
  bytes_ = 0;
}

void TriangleBuffers::draw() const {
  if (empty()) return;
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
}

}  // namespace rl
