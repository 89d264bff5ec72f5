#pragma once
// What a GPU pays for a frame's ops, from the op-counting render (gl/op_count_buffer.h): each
// fragment's executed ops by kind (core/op_kinds.h), reduced the way a GPU runs fragments --
// in 8 x 4 lockstep groups (kWarpTileWidth x kWarpTileHeight, metrics/fragment_cost.h) that take
// as long as their slowest lane. Per kind, a tile pays its fragments times the largest
// per-fragment count among its pixels; `warp_<kind>_ops` is the tiles' total over their pixels
// (every pixel of the viewport, shaded or not), so the total a frame pays is it times
// width x height: what the GPU cost model (core/cost_model.h) weighs. Where the render counted
// one tile in group_stride^2 (PixelOpCounts), the total and the pixels are those tiles': a
// stratified sample of the frame whose mean estimates the whole.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "core/op_kinds.h"

namespace rl {

struct OpCost {
  std::array<double, kOpKinds> warp_ops_per_px{};  // NaN when the render counted nothing
  double counted_fragments = 0;                    // fragments that wrote their counts
  // Nothing counted (no op-counting frame drawn): every column NaN, so rows leave them empty.
  static OpCost none();
  // (name, value) in rows.csv's column order.
  std::vector<std::pair<std::string, double>> named() const;
};

OpCost op_cost(const PixelOpCounts& counts);

// A frame's cost with that of another pass it draws first into a target of its own,
// `pixel_ratio` times the frame's pixels (the shadow map of scene_shadows): per frame pixel, the
// two added. A pass that shaded no fragment adds nothing.
OpCost with_pass(const OpCost& frame, const OpCost& pass, double pixel_ratio);

// The column of kind k's lockstep ops per pixel, e.g. "warp_float_ops".
std::string warp_ops_column(int kind);

}  // namespace rl
