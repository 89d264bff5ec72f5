#pragma once
// GPU buffers of an indexed triangle mesh with three vec3 attributes per vertex -- position,
// normal, colour at locations 0, 1, 2 -- as the scene's plain objects and the cell complex's
// rasterised meshes draw them.
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

namespace rl {

class TriangleBuffers {
 public:
  TriangleBuffers() = default;
  // `position`, `normal`, `color` per vertex (the same length); counter-clockwise or not, as
  // the caller culls.
  TriangleBuffers(const std::vector<glm::vec3>& position, const std::vector<glm::vec3>& normal,
                  const std::vector<glm::vec3>& color, const std::vector<glm::uvec3>& triangles);
  ~TriangleBuffers();
  TriangleBuffers(const TriangleBuffers&) = delete;
  TriangleBuffers& operator=(const TriangleBuffers&) = delete;
  TriangleBuffers(TriangleBuffers&& other) noexcept;
  TriangleBuffers& operator=(TriangleBuffers&& other) noexcept;

  bool empty() const { return index_count_ == 0; }
  size_t bytes() const { return bytes_; }  // vertex and index buffers
  void draw() const;                       // glDrawElements of every triangle

 private:
  void release();
  GLuint vao_ = 0, vbo_ = 0, ibo_ = 0;
  GLsizei index_count_ = 0;
  size_t bytes_ = 0;
};

}  // namespace rl
