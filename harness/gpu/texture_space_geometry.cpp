#include "gpu/texture_space_geometry.h"

#include <algorithm>
#include <utility>

#include "gl/context.h"

namespace rl {

void append_cube_face(std::vector<glm::vec3>& tris, glm::ivec3 cell, int f, int n) {
  const int a = f / 2, b = (a + 1) % 3, c = (a + 2) % 3;
  auto corner = [&](int sb, int sc) {
    glm::vec3 p(cell);
    p[a] += float(f % 2);
    p[b] += float(sb);
    p[c] += float(sc);
    return p / float(n);
  };
  glm::vec3 q[4] = {corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)};
  // (b, c, a) is right-handed, so this order is counter-clockwise seen from +a in texture
  // space: from outside for side 1. The world mirrors depth, which flips the winding:
  // counter-clockwise from outside in the world for side 0 only.
  if (f % 2 == 1) std::swap(q[1], q[3]);
  tris.insert(tris.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
}

PositionBuffer::~PositionBuffer() {
  if (vao_) glDeleteVertexArrays(1, &vao_);
  if (vbo_) glDeleteBuffers(1, &vbo_);
}

void PositionBuffer::set(const std::vector<glm::vec3>& positions) {
  GlContext::shared();
  if (!vao_) {
    glCreateVertexArrays(1, &vao_);
    glEnableVertexArrayAttrib(vao_, 0);
    glVertexArrayAttribFormat(vao_, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao_, 0, 0);
  }
  const size_t need = std::max<size_t>(1, positions.size());
  if (need > capacity_) {
    // A mutable store, grown as needed: slices change with the view.
    if (vbo_) glDeleteBuffers(1, &vbo_);
    glCreateBuffers(1, &vbo_);
    glNamedBufferData(vbo_, GLsizeiptr(need * sizeof(glm::vec3)), nullptr, GL_DYNAMIC_DRAW);
    glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, sizeof(glm::vec3));
    capacity_ = need;
  }
  if (!positions.empty())
    glNamedBufferSubData(vbo_, 0, GLsizeiptr(positions.size() * sizeof(glm::vec3)),
                         positions.data());
  vertices_ = GLsizei(positions.size());
}

void PositionBuffer::draw_front_faces() const {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  draw_triangles();
  glDisable(GL_CULL_FACE);
}

void PositionBuffer::draw(GLenum mode, GLint first, GLsizei count) const {
  if (!vao_ || count <= 0) return;
  glBindVertexArray(vao_);
  glDrawArrays(mode, first, count);
}

}  // namespace rl
