#pragma once
// A min-depth quadtree over a heightfield's bilinear cells, for hierarchical empty-space
// skipping (Tevs, Ihrke & Seidel 2008's maximum mipmaps, in ReliefLab's depth convention:
// depth grows downwards, so the highest point of a region is its minimum depth).
//
// Cells are those of the centerline walk (harness/glsl/centerline_walk.glsl): cell (i, j)
// spans texel centres i..i+1 and j..j+1 (wrapping), so a W x H map has W x H cells and the
// bilinear surface over a cell never rises above its four corners. Level 0 holds each cell's
// least corner depth; level k + 1 the least of its 2 x 2 children at level k. A ray whose depth
// stays below a node's value over the node's extent cannot meet the surface there.
#include <vector>

#include "relief/relief_map.h"

namespace rl {

struct MinDepthPyramid {
  int width = 0, height = 0;              // cells at level 0 (the map's texels)
  std::vector<std::vector<float>> level;  // level[k] has (width >> k) x (height >> k) nodes
  int levels() const { return int(level.size()); }
};

// Levels a W x H map supports: while both sides halve exactly (nodes must tile the wrapped
// map at every level), down to a 1-node side. A 1024^2 map has 11 (1024^2 ... 1^2); 768^2
// has 9 (768^2 ... 3^2); an odd side has 1.
int quadtree_levels(int width, int height);

// The pyramid of `map`'s level-0 depths. Stored values are lowered by `margin` so that a
// GPU's own conversion of 8-bit depths never puts a texel above its node's bound.
MinDepthPyramid build_min_depth_pyramid(const ReliefMap& map, float margin = 1e-6f);

}  // namespace rl
