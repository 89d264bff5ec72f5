#pragma once
// The 2D DDA of Amanatides & Woo: the unit grid cells a ray crosses, in order, with the
// parameter interval it spends in each. Used by the exact reference (texel cells) and by the
// truth (tile cells). Bounded: a ray crosses at most |dx| + |dy| cell edges per unit t, so
// the walk visits at most that many cells (+ a few) over [t_min, t_max].
#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/glm.hpp>

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

// Texture-space truths repeat one tile: calls query(local_origin, t0, t1) for each tile cell
// (I, J) = [offset + I, offset + I + 1) x ... the ray (u, v, depth) crosses, with the origin
// moved into the tile at I = J = 0, until query returns true. The intervals overlap slightly,
// so a hit exactly on a tile edge is found from either side.
template <typename Query>
bool walk_tiles(const glm::dvec3& origin, const glm::dvec3& direction, double t_min, double t_max,
                const glm::dvec2& offset, Query&& query) {
  return walk_grid_2d(origin.x - offset.x, origin.y - offset.y, direction.x, direction.y, t_min,
                      t_max, [&](long I, long J, double t_enter, double t_exit) {
                        const double eps = 1e-7 * (1.0 + t_exit);
                        const glm::dvec3 local = origin - glm::dvec3(double(I), double(J), 0.0);
                        return query(local, std::max(t_min, t_enter - eps),
                                     std::min(t_max, t_exit + eps));
                      });
}

}  // namespace rl
