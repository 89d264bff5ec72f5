#pragma once
// The 2D DDA of Amanatides & Woo: the unit grid cells a ray crosses, in order, with the
// parameter interval it spends in each. Used by the exact reference (texel cells) and by the
// truth (tile cells). Bounded: a ray crosses at most |dx| + |dy| cell edges per unit t, so
// the walk visits at most that many cells (+ a few) over [t_min, t_max].
#include <algorithm>
#include <cmath>
#include <limits>

namespace rl {

// Calls visit(i, j, t_enter, t_exit) for each cell (i, j) = [i, i+1) x [j, j+1) that the
// ray (x0 + t dx, y0 + t dy) crosses for t in [t_min, t_max], until visit returns true
// (found) or the ray leaves the interval. Returns whether visit returned true.
template <typename Visit>
bool walk_grid_2d(double x0, double y0, double dx, double dy, double t_min, double t_max,
                  Visit&& visit) {
  const double inf = std::numeric_limits<double>::infinity();
  const double xs = x0 + dx * t_min, ys = y0 + dy * t_min;
  long i = static_cast<long>(std::floor(xs)), j = static_cast<long>(std::floor(ys));
  const int step_i = dx > 0 ? 1 : (dx < 0 ? -1 : 0);
  const int step_j = dy > 0 ? 1 : (dy < 0 ? -1 : 0);
  const double delta_i = step_i ? 1.0 / std::abs(dx) : inf;
  const double delta_j = step_j ? 1.0 / std::abs(dy) : inf;
  double next_i =
      step_i > 0 ? t_min + (i + 1 - xs) / dx : (step_i < 0 ? t_min + (xs - i) / -dx : inf);
  double next_j =
      step_j > 0 ? t_min + (j + 1 - ys) / dy : (step_j < 0 ? t_min + (ys - j) / -dy : inf);
  const double span = (std::abs(dx) + std::abs(dy)) * (t_max - t_min);
  const long max_cells = static_cast<long>(std::min(span, 1e8)) + 4;
  double t_enter = t_min;
  for (long n = 0; n < max_cells && t_enter <= t_max; ++n) {
    const double t_exit = std::min({next_i, next_j, t_max});
    if (visit(i, j, t_enter, t_exit)) return true;
    if (t_exit >= t_max) break;
    t_enter = t_exit;
    if (next_i <= next_j) {
      i += step_i;
      next_i += delta_i;
    } else {
      j += step_j;
      next_j += delta_j;
    }
  }
  return false;
}

}  // namespace rl
