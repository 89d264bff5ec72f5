#pragma once
// Slab test of a ray against an axis-aligned box.
#include <algorithm>
#include <limits>
#include <utility>

#include <glm/glm.hpp>

namespace rl {

// Where the ray o + t d, t >= 0, is inside the box [lo, hi]: [t_in, t_out]; false when it
// misses (a ray parallel to a slab and outside it misses).
inline bool clip_ray_to_box(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& lo,
                            const glm::dvec3& hi, double& t_in, double& t_out) {
  t_in = 0;
  t_out = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    double t0 = (lo[a] - o[a]) / d[a], t1 = (hi[a] - o[a]) / d[a];
    if (t0 > t1) std::swap(t0, t1);
    t_in = std::max(t_in, t0);
    t_out = std::min(t_out, t1);
  }
  return t_in < t_out;
}

}  // namespace rl
