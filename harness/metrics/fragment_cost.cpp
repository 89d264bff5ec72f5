#include "metrics/fragment_cost.h"

#include <algorithm>
#include <limits>

namespace rl {

double lockstep_fetches_mean(const FragmentCounts& c, int tile_w, int tile_h) {
  double cost = 0, fragments = 0;
  for (int y0 = 0; y0 < c.height; y0 += tile_h)
    for (int x0 = 0; x0 < c.width; x0 += tile_w) {
      double tile_fragments = 0, slowest = 0;
      for (int y = y0; y < std::min(y0 + tile_h, c.height); ++y)
        for (int x = x0; x < std::min(x0 + tile_w, c.width); ++x) {
          const size_t i = size_t(y) * c.width + x;
          tile_fragments += c.fragments[i];
          if (c.fragments[i]) slowest = std::max(slowest, double(c.fetch_max[i]));
        }
      cost += tile_fragments * slowest;
      fragments += tile_fragments;
    }
  return fragments > 0 ? cost / fragments : std::numeric_limits<double>::quiet_NaN();
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
  out.warp_fetches_mean = lockstep_fetches_mean(c, kWarpTileWidth, kWarpTileHeight);
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
          {"iterations_mean", iterations_mean},
          {"iterations_max", iterations_max}};
}

}  // namespace rl
