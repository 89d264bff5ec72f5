#pragma once
// A pyramid of window minima over a heightfield's bilinear cells, for empty-space skipping with
// unaligned steps (techniques/relief_window_exact): level k, one value per block of b = 2^k x
// 2^k texels, holds the least depth of every cell that a step of at most b texels (along each
// axis) from any point of the block can reach. Depth grows downwards, so that least depth is
// the highest the surface rises there: a ray whose depth at the step's end is still below it
// (numerically: smaller) meets nothing during the step. A ray that moves one way along an axis
// reaches only the block's cells and those ahead: a window per way is two blocks wide, not
// three, so it rises less high and turns fewer steps away.
#include <vector>

namespace rl {

// Level k of the pyramid over `cells` (W x H least corner depths of the bilinear cells,
// MinDepthPyramid's level 0, wrapping; W and H multiples of b), row by row, (W / b) x (H / b).
// A point of block I has texture coordinate u with u W in [I b, (I + 1) b), texel-centre
// coordinate X = u W - 0.5; a step of at most b texels keeps X within
// [I b - 0.5 - b, (I + 1) b - 0.5 + b], which cells (I - 1) b - 1 .. (I + 2) b - 1 cover with
// half a texel to spare on each side, so a GPU's rounding of u at a block's edge cannot take
// the step outside its window.
// `way_x`, `way_y`: which way the steps go along each axis: +1 (X grows) or -1, or 0 for
// either. Moving up (+1) X stays within [I b - 0.5, (I + 2) b - 0.5], cells I b - 1 ..
// (I + 2) b - 1; moving down, cells (I - 1) b - 1 .. (I + 1) b - 1; both with half a texel to
// spare.
std::vector<float> window_level(const std::vector<float>& cells, int W, int H, int b, int way_x = 0,
                                int way_y = 0);

}  // namespace rl
