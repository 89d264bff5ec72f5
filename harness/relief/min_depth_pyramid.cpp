#include "relief/min_depth_pyramid.h"

#include <algorithm>

namespace rl {

int quadtree_levels(int width, int height) {
  int levels = 1;
  while (width % 2 == 0 && height % 2 == 0 && width > 1 && height > 1) {
    width /= 2;
    height /= 2;
    ++levels;
  }
  return levels;
}

MinDepthPyramid build_min_depth_pyramid(const ReliefMap& map, float margin) {
  MinDepthPyramid p;
  p.width = map.width;
  p.height = map.height;
  const int levels = quadtree_levels(map.width, map.height);
  p.level.resize(size_t(levels));
  std::vector<float>& cells = p.level[0];
  cells.resize(size_t(map.width) * map.height);
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x)
      cells[size_t(y) * map.width + x] =
          std::min({map.depth_texel(x, y), map.depth_texel(x + 1, y), map.depth_texel(x, y + 1),
                    map.depth_texel(x + 1, y + 1)}) -
          margin;
  for (int k = 1; k < levels; ++k) {
    const int w = map.width >> k, h = map.height >> k, cw = map.width >> (k - 1);
    const std::vector<float>& child = p.level[size_t(k - 1)];
    std::vector<float>& node = p.level[size_t(k)];
    node.resize(size_t(w) * h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t c = size_t(2 * y) * cw + 2 * x;
        node[size_t(y) * w + x] =
            std::min({child[c], child[c + 1], child[c + cw], child[c + cw + 1]});
      }
  }
  return p;
}

}  // namespace rl
