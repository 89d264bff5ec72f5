#pragma once
// What the fragments of a G-buffer render fetched, per pixel, as the render target counts them
// (gl/render_target.h) and the cost metrics read them (metrics/fragment_cost.h).
#include <cstdint>
#include <vector>

namespace rl {

// Per pixel (row 0 at the bottom, as GL reads back): fragments shaded, their fetches' sum and
// the largest fetch count of any one of them, and the same two for their search iterations.
struct FragmentCounts {
  int width = 0, height = 0;
  std::vector<uint32_t> fragments, fetch_sum, fetch_max, iteration_sum, iteration_max;
  void resize(int w, int h) {
    width = w;
    height = h;
    const size_t n = size_t(w) * h;
    fragments.assign(n, 0);
    fetch_sum.assign(n, 0);
    fetch_max.assign(n, 0);
    iteration_sum.assign(n, 0);
    iteration_max.assign(n, 0);
  }
};

}  // namespace rl
