#include "technique/quadtree_technique.h"

namespace rl {

QuadtreeTechnique::~QuadtreeTechnique() {
  if (texture_) glDeleteTextures(1, &texture_);
}

void QuadtreeTechnique::prepare(const ReliefMap& map) {
  const MinDepthPyramid pyramid = build_min_depth_pyramid(map);
  top_ = pyramid.levels() - 1;
  // Levels 1 and up stacked in rows (min_depth_quadtree.glsl): level k at row H - (H >> (k-1)).
  // Level 0 is not uploaded: the search gathers a cell's corners themselves.
  const int width = std::max(1, pyramid.width / 2), height = std::max(1, pyramid.height);
  std::vector<float> atlas(size_t(width) * height, 0.0f);
  for (int k = 1; k <= top_; ++k) {
    const int w = pyramid.width >> k, h = pyramid.height >> k;
    const int row0 = pyramid.height - (pyramid.height >> (k - 1));
    for (int y = 0; y < h; ++y)
      std::copy_n(pyramid.level[size_t(k)].begin() + size_t(y) * w, w,
                  atlas.begin() + size_t(row0 + y) * width);
  }
  if (texture_) glDeleteTextures(1, &texture_);
  glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
  glTextureStorage2D(texture_, 1, GL_R32F, width, height);
  glTextureSubImage2D(texture_, 0, 0, 0, width, height, GL_RED, GL_FLOAT, atlas.data());
  glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  bytes_ = top_ > 0 ? atlas.size() * sizeof(float) : 0;
}

void QuadtreeTechnique::bind_resources(GLuint program) const {
  glBindTextureUnit(4, texture_);
  glProgramUniform1i(program, glGetUniformLocation(program, "rl_quadtree_top"), top_);
}

}  // namespace rl
