#pragma once
// Geometry in the relief's texture space (u, v, depth), drawn through
// harness/glsl/texture_space.vert: a cell complex's proxy faces, a heightfield object's cube,
// depth slices.
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

namespace rl {

// Appends face f (2 * axis + side) of the cell at integer corner `cell` of an n^3 grid over the
// unit cube as two triangles, counter-clockwise seen from outside in the world (texture space
// mirrors depth, which flips the winding), so back faces can be culled.
void append_cube_face(std::vector<glm::vec3>& triangles, glm::ivec3 cell, int face, int n);

// Positions only (location 0), uploaded once or replaced per frame (set()).
class PositionBuffer {
 public:
  PositionBuffer() = default;
  ~PositionBuffer();
  PositionBuffer(const PositionBuffer&) = delete;
  PositionBuffer& operator=(const PositionBuffer&) = delete;
  void set(const std::vector<glm::vec3>& positions);
  // glDrawArrays(mode, first, count) on the buffer's vertices.
  void draw(GLenum mode, GLint first, GLsizei count) const;
  void draw_triangles() const { draw(GL_TRIANGLES, 0, vertices_); }
  // A closed proxy's front faces only, depth-tested (GL_LESS): each pixel's ray enters once and
  // the shader's written depth resolves the rest.
  void draw_front_faces() const;
  GLsizei vertices() const { return vertices_; }
  size_t bytes() const { return size_t(vertices_) * sizeof(glm::vec3); }

 private:
  GLuint vao_ = 0, vbo_ = 0;
  GLsizei vertices_ = 0;
  size_t capacity_ = 0;
};

}  // namespace rl
