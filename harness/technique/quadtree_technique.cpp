#include "technique/quadtree_technique.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace rl {
namespace {

// What the stored bounds are lowered by (harness/glsl/min_depth_quadtree.glsl's
// RL_MIN_DEPTH_MARGIN).
constexpr float kMargin = 1e-6f;

// An RGBA32UI texture of `texels` (4 words each), nearest-sampled.
GLuint uint_texture(const std::vector<uint32_t>& texels, int width, int height) {
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, GL_RGBA32UI, width, height);
  glTextureSubImage2D(t, 0, 0, 0, width, height, GL_RGBA_INTEGER, GL_UNSIGNED_INT, texels.data());
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return t;
}

// Level 1's nodes as blocks of their 3 x 3 corner depths, 8 bits each (an 8-bit map's depths are
// whole multiples of 1/255), row by row, low bytes first (x, y, z: bytes 0-3, 4-7, 8): one fetch
// reads a node's four cells.
std::vector<uint32_t> cell_blocks(const ReliefMap& map) {
  const int w = map.width / 2, h = map.height / 2;
  std::vector<uint32_t> out(size_t(w) * h * 4, 0u);
  for (int by = 0; by < h; ++by)
    for (int bx = 0; bx < w; ++bx)
      for (int n = 0; n < 9; ++n) {
        const float d = map.depth_texel(2 * bx + n % 3, 2 * by + n / 3);  // wraps
        const uint32_t byte = uint32_t(std::lround(double(d) * 255.0));
        out[(size_t(by) * w + bx) * 4 + size_t(n / 4)] |= byte << (8 * (n % 4));
      }
  return out;
}

// Levels 1 to top - 2 of the quadtree as blocks of 4 x 4 nodes' bounds, 8 bits each (an 8-bit
// map's least depths are whole multiples of 1/255), row by row, low bytes first: one fetch reads
// a node, its siblings and their children (levels l + 1 and l). Level l's
// (W >> (l + 2)) x (H >> (l + 2)) blocks start at row (H >> 2) - (H >> (l + 1)).
std::vector<uint32_t> bound_blocks(const MinDepthPyramid& pyramid, int top, float margin) {
  const int width = std::max(1, pyramid.width >> 3), height = std::max(1, pyramid.height >> 2);
  std::vector<uint32_t> out(size_t(width) * height * 4, 0u);
  for (int l = 1; l + 2 <= top; ++l) {
    const int nodes_w = pyramid.width >> l, blocks_w = nodes_w >> 2,
              blocks_h = pyramid.height >> (l + 2);
    const int row0 = (pyramid.height >> 2) - (pyramid.height >> (l + 1));
    for (int by = 0; by < blocks_h; ++by)
      for (int bx = 0; bx < blocks_w; ++bx)
        for (int n = 0; n < 16; ++n) {
          const float bound =
              pyramid.level[size_t(l)][size_t(4 * by + n / 4) * nodes_w + 4 * bx + n % 4];
          const uint32_t byte = uint32_t(std::lround(double(bound + margin) * 255.0));
          out[(size_t(row0 + by) * width + bx) * 4 + size_t(n / 4)] |= byte << (8 * (n % 4));
        }
  }
  return out;
}

}  // namespace

QuadtreeTechnique::~QuadtreeTechnique() {
  if (texture_) glDeleteTextures(1, &texture_);
  for (GLuint t : {blocks_, bound_blocks_})
    if (t) glDeleteTextures(1, &t);
}

void QuadtreeTechnique::prepare(const ReliefMap& map) {
  const MinDepthPyramid pyramid = build_min_depth_pyramid(map, kMargin);
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
  for (GLuint* t : {&blocks_, &bound_blocks_})
    if (*t) glDeleteTextures(1, t);
  blocks_ = bound_blocks_ = 0;
  if (uses_blocks() && map.quantized && top_ > 0) {
    blocks_ = uint_texture(cell_blocks(map), map.width / 2, map.height / 2);
    bytes_ += size_t(map.width / 2) * (map.height / 2) * 16;
    const int w = std::max(1, map.width >> 3), h = std::max(1, map.height >> 2);
    bound_blocks_ = uint_texture(bound_blocks(pyramid, top_, kMargin), w, h);
    bytes_ += size_t(w) * h * 16;
  }
}

void QuadtreeTechnique::bind_resources(GLuint program) const {
  glBindTextureUnit(4, texture_);
  glProgramUniform1i(program, glGetUniformLocation(program, "rl_quadtree_top"), top_);
  if (uses_blocks()) {
    glBindTextureUnit(5, blocks_);
    glBindTextureUnit(6, bound_blocks_);
    glProgramUniform1i(program, glGetUniformLocation(program, "rl_blocks_built"), blocks_ != 0);
  }
}

}  // namespace rl
