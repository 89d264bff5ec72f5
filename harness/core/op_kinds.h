#pragma once
// The kinds of work a fragment's op counts are split into (gl/spirv_op_counts.h counts them,
// metrics/op_cost.h reduces them per lockstep group, the GPU cost model weighs them).
#include <array>
#include <cstdint>
#include <vector>

namespace rl {

enum class OpKind { Fetch, Float, Special, Int, Branch, DynamicIndex };
inline constexpr int kOpKinds = 6;

// The short name of each kind, in OpKind's order: the suffix of its columns and model weights.
inline const std::array<const char*, kOpKinds> kOpKindNames = {"fetch", "float",  "special",
                                                               "int",   "branch", "dynamic_index"};

using OpCounts = std::array<uint64_t, kOpKinds>;

// A GPU's lockstep group, as the cost columns model it: an 8 x 4 tile of pixels (32 lanes).
inline constexpr int kWarpTileWidth = 8, kWarpTileHeight = 4;

// Per pixel (row 0 at the bottom, as GL reads back): the fragments the op-counting render shaded
// there and the ops they executed, by kind, summed over them. Only the lockstep groups whose
// column and row of groups are multiples of group_stride were counted (gl/op_counting.h).
struct PixelOpCounts {
  int width = 0, height = 0;
  int group_stride = 1;
  std::vector<uint32_t> fragments;
  std::array<std::vector<uint32_t>, kOpKinds> ops;
};

}  // namespace rl
