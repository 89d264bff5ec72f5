#include "metrics/op_cost.h"

#include <algorithm>
#include <limits>

#include "core/columns.h"
#include "metrics/fragment_cost.h"

namespace rl {
namespace {

std::vector<ColumnSpec> op_cost_specs() {
  std::vector<ColumnSpec> specs;
  const char* meaning[kOpKinds] = {
      "texture reads",
      "float arithmetic, comparisons and cheap functions, per component",
      "division, sqrt, exp, log, pow and trigonometry, per component",
      "integer, bit and boolean arithmetic, per component",
      "conditional branches, switches and discards",
      "accesses into a local array at an index known only at run time"};
  for (int k = 0; k < kOpKinds; ++k)
    specs.push_back({warp_ops_column(k), "ops / px",
                     std::string("lockstep cost of ") + meaning[k] +
                         ": 8 x 4 tiles pay their slowest fragment's count, per pixel (the "
                         "op-counting render, every pass; over the tiles it counted, "
                         "[sweep] op_count_stride)"});
  specs.push_back(
      {"op_counted_fragments", "fragments",
       "fragments that wrote their op counts in the op-counting render (in the tiles it "
       "counted)"});
  return specs;
}

const ColumnDeclaration op_cost_columns("metrics (op cost)", op_cost_specs());

}  // namespace

std::string warp_ops_column(int kind) {
  return std::string("warp_") + kOpKindNames[kind] + "_ops";
}

OpCost op_cost(const PixelOpCounts& c) {
  OpCost out;
  std::array<double, kOpKinds> total{};
  double pixels = 0;  // of the groups counted
  const int stride = std::max(c.group_stride, 1);
  for (int y0 = 0; y0 < c.height; y0 += kWarpTileHeight * stride)
    for (int x0 = 0; x0 < c.width; x0 += kWarpTileWidth * stride) {
      const int x1 = std::min(x0 + kWarpTileWidth, c.width);
      const int y1 = std::min(y0 + kWarpTileHeight, c.height);
      pixels += double(x1 - x0) * (y1 - y0);
      double fragments = 0;
      std::array<double, kOpKinds> slowest{};
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          const size_t i = size_t(y) * c.width + x;
          if (!c.fragments[i]) continue;
          fragments += c.fragments[i];
          for (int k = 0; k < kOpKinds; ++k)
            slowest[k] = std::max(slowest[k], double(c.ops[k][i]) / c.fragments[i]);
        }
      out.counted_fragments += fragments;
      for (int k = 0; k < kOpKinds; ++k) total[k] += fragments * slowest[k];
    }
  for (int k = 0; k < kOpKinds; ++k)
    out.warp_ops_per_px[k] = out.counted_fragments > 0 && pixels > 0
                                 ? total[k] / pixels
                                 : std::numeric_limits<double>::quiet_NaN();
  return out;
}

OpCost with_pass(const OpCost& frame, const OpCost& pass, double pixel_ratio) {
  if (!(pass.counted_fragments > 0)) return frame;
  OpCost out = frame;
  for (int k = 0; k < kOpKinds; ++k)
    out.warp_ops_per_px[k] += pass.warp_ops_per_px[k] * pixel_ratio;
  out.counted_fragments += pass.counted_fragments;
  return out;
}

OpCost OpCost::none() {
  OpCost out;
  out.warp_ops_per_px.fill(std::numeric_limits<double>::quiet_NaN());
  out.counted_fragments = std::numeric_limits<double>::quiet_NaN();
  return out;
}

std::vector<std::pair<std::string, double>> OpCost::named() const {
  std::vector<std::pair<std::string, double>> out;
  for (int k = 0; k < kOpKinds; ++k) out.emplace_back(warp_ops_column(k), warp_ops_per_px[k]);
  out.emplace_back("op_counted_fragments", counted_fragments);
  return out;
}

}  // namespace rl
