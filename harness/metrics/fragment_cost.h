#pragma once
// The cost a GPU would pay for a frame, from what every shaded fragment fetched.
//
// The G-buffer render counts, per pixel, every fragment the technique's passes shade -- kept or
// discarded, in every pass -- with the sum and the largest of their texture fetches
// (harness/glsl/gbuffer_outputs.glsl). From those:
// - frag_fetches_mean / frag_fetches_max: fetches per shaded fragment, over all of them, and
//   `fragments`, their count summed over passes. fetches_mean (metrics.h) is per covered pixel
//   of the final image; a discarded ray (a miss under a box proxy, an impostor's side, a cell
//   complex's empty cells) costs here what it walked.
// - warp_fetches_mean: GPUs run fragments in lockstep groups that cost what their slowest lane
//   costs. Pixels are grouped into 8 x 4 tiles (x across, y up from the frame's bottom-left
//   pixel, as gl_FragCoord counts them; 32 lanes, an NVIDIA warp); a tile costs its largest
//   per-fragment fetch count times its fragments, and the mean is the tiles' total over all
//   fragments. quad_fetches_mean: the same for 2 x 2 quads, the smallest group any GPU shades.
//   The passes of a multi-pass technique are pooled per tile: their fragments share one largest
//   count, which bounds the sum of each pass's own groups from above.
// - warp_fetches_per_px: the same tiles' total over the pixels at least one fragment was shaded
//   at: the frame's lockstep cost per pixel it drew. Per fragment, a technique of 64 passes of
//   two fetches each costs 2 like a 2-fetch single pass; per pixel it costs 128. It equals
//   warp_fetches_mean where every pixel is shaded once, and is the default cost of the Pareto
//   fronts (output/pareto.h).
// - iterations_mean / iterations_max: search-loop iterations per shaded fragment
//   (harness/glsl/search_cost.glsl), over the same fragments. They part from the fetch counts
//   where a step reads several textures (multilayer groups, cube faces: fewer iterations) or a
//   step reads none (a quadtree's level change, a DDA cell decided from its entry: more).
#include <string>
#include <utility>
#include <vector>

#include "core/fragment_counts.h"
#include "core/op_kinds.h"  // kWarpTileWidth, kWarpTileHeight

namespace rl {

struct FragmentCost {
  double fragments = 0;
  double frag_fetches_mean = 0, frag_fetches_max = 0;
  double quad_fetches_mean = 0, warp_fetches_mean = 0, warp_fetches_per_px = 0;
  double iterations_mean = 0, iterations_max = 0;
  // (name, value) in rows.csv's column order; means NaN when no fragment was shaded.
  std::vector<std::pair<std::string, double>> named() const;
};

// The lockstep cost of `counts` in tiles of tile_w x tile_h pixels: each tile's fragments times
// its largest fetch count, summed over the tiles, with the fragments and the pixels shaded.
struct LockstepCost {
  double fetches = 0, fragments = 0, pixels = 0;
};
LockstepCost lockstep_cost(const FragmentCounts& counts, int tile_w, int tile_h);
// Its mean over fragments (NaN when none was shaded).
double lockstep_fetches_mean(const FragmentCounts& counts, int tile_w, int tile_h);
FragmentCost fragment_cost(const FragmentCounts& counts);

}  // namespace rl
