#pragma once
// Base for techniques that search over the min-depth quadtree of the bilinear cells
// (relief/min_depth_pyramid.h, harness/glsl/min_depth_quadtree.glsl): prepare() builds the
// pyramid on the CPU and uploads levels 1 and up as one R32F texture, bound to unit 4. Building it
// is a single pass over the map (milliseconds at 1024^2), so it is rebuilt rather than cached.
#include "relief/min_depth_pyramid.h"
#include "technique/shader_technique.h"

namespace rl {

class QuadtreeTechnique : public ShaderTechnique {
 public:
  using ShaderTechnique::ShaderTechnique;
  ~QuadtreeTechnique() override;
  void prepare(const ReliefMap& map) override;
  size_t memory_bytes() const override { return bytes_; }

 protected:
  void bind_resources(GLuint program) const override;
  // Whether the search may read packed blocks, built on 8-bit maps only: a level-1 node's 3 x 3
  // corner depths in one RGBA32UI texel (rl_cell_blocks, unit 5), and 4 x 4 nodes' bounds at
  // 8 bits each (rl_bound_blocks, unit 6).
  virtual bool uses_blocks() const { return false; }

 private:
  GLuint texture_ = 0, blocks_ = 0, bound_blocks_ = 0;
  int top_ = 0;
  size_t bytes_ = 0;
};

}  // namespace rl
