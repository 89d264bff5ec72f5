#include "metrics/fragment_cost.h"

#include <algorithm>
#include <limits>

#include "core/columns.h"

namespace rl {
namespace {

// The columns FragmentCost::named() writes (fragment_cost.h defines each).
const ColumnDeclaration fragment_cost_columns(
    "metrics (fragment cost)",
    {{"fragments", "fragments", "fragments the technique's passes shaded, kept or discarded"},
     ColumnSpec{"frag_fetches_mean", "fetches", "texture fetches per shaded fragment, every pass"}
         .compared(1e-9, 0.02)
         .reported(),
     {"frag_fetches_max", "fetches", "the most fetches one shaded fragment paid"},
     {"quad_fetches_mean", "fetches",
      "lockstep cost of 2 x 2 quads: each quad pays its slowest fragment, per fragment"},
     ColumnSpec{
         "warp_fetches_mean", "fetches",
         "lockstep cost of 32-lane groups (8 x 4 tiles): each pays its slowest fragment, per "
         "fragment"}
         .compared(1e-9, 0.02)
         .reported(),
     ColumnSpec{
         "warp_fetches_per_px", "fetches",
         "the same warp total per pixel shaded at least once: the frame's cost per pixel drawn, "
         "the default Pareto cost"}
         .compared(1e-9, 0.02)
         .reported(),
     ColumnSpec{"iterations_mean", "iterations",
                "passes through the search loops per shaded fragment"}
         .compared(1e-9, 0.02)
         .reported(),
     {"iterations_max", "iterations", "the most search-loop passes of one fragment"}});

}  // namespace

LockstepCost lockstep_cost(const FragmentCounts& c, int tile_w, int tile_h) {
  LockstepCost total;
  for (int y0 = 0; y0 < c.height; y0 += tile_h)
    for (int x0 = 0; x0 < c.width; x0 += tile_w) {
      double tile_fragments = 0, slowest = 0;
      for (int y = y0; y < std::min(y0 + tile_h, c.height); ++y)
        for (int x = x0; x < std::min(x0 + tile_w, c.width); ++x) {
          const size_t i = size_t(y) * c.width + x;
          tile_fragments += c.fragments[i];
          if (c.fragments[i]) {
            slowest = std::max(slowest, double(c.fetch_max[i]));
            ++total.pixels;
          }
        }
      total.fetches += tile_fragments * slowest;
      total.fragments += tile_fragments;
    }
  return total;
}

double lockstep_fetches_mean(const FragmentCounts& c, int tile_w, int tile_h) {
  const LockstepCost t = lockstep_cost(c, tile_w, tile_h);
  return t.fragments > 0 ? t.fetches / t.fragments : std::numeric_limits<double>::quiet_NaN();
}

FragmentCost fragment_cost(const FragmentCounts& c) {
  FragmentCost out;
  double fetches = 0, iterations = 0;
  for (size_t i = 0; i < c.fragments.size(); ++i) {
    if (!c.fragments[i]) continue;
    out.fragments += c.fragments[i];
    fetches += c.fetch_sum[i];
    iterations += c.iteration_sum[i];
    out.frag_fetches_max = std::max(out.frag_fetches_max, double(c.fetch_max[i]));
    out.iterations_max = std::max(out.iterations_max, double(c.iteration_max[i]));
  }
  out.quad_fetches_mean = lockstep_fetches_mean(c, 2, 2);
  const LockstepCost warp = lockstep_cost(c, kWarpTileWidth, kWarpTileHeight);
  out.warp_fetches_mean =
      warp.fragments > 0 ? warp.fetches / warp.fragments : std::numeric_limits<double>::quiet_NaN();
  out.warp_fetches_per_px =
      warp.pixels > 0 ? warp.fetches / warp.pixels : std::numeric_limits<double>::quiet_NaN();
  if (out.fragments == 0) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    out.frag_fetches_mean = out.frag_fetches_max = out.iterations_mean = out.iterations_max = nan;
  } else {
    out.frag_fetches_mean = fetches / out.fragments;
    out.iterations_mean = iterations / out.fragments;
  }
  return out;
}

std::vector<std::pair<std::string, double>> FragmentCost::named() const {
  return {{"fragments", fragments},
          {"frag_fetches_mean", frag_fetches_mean},
          {"frag_fetches_max", frag_fetches_max},
          {"quad_fetches_mean", quad_fetches_mean},
          {"warp_fetches_mean", warp_fetches_mean},
          {"warp_fetches_per_px", warp_fetches_per_px},
          {"iterations_mean", iterations_mean},
          {"iterations_max", iterations_max}};
}

}  // namespace rl
