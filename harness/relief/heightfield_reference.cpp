#include "relief/heightfield_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/grid_walk.h"

namespace rl {

double smallest_root_in(double a, double b, double c, double lo, double hi) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double roots[2];
  int n = 0;
  const double scale = std::max({std::abs(a), std::abs(b), std::abs(c), 1e-300});
  if (std::abs(a) <= 1e-14 * scale) {
    if (std::abs(b) > 0) roots[n++] = -c / b;
  } else {
    double disc = b * b - 4 * a * c;
    if (disc < 0) {
      // Tangency lost to rounding: accept a double root if the discriminant is tiny.
      if (disc > -1e-12 * b * b)
        disc = 0;
      else
        return nan;
    }
    double sq = std::sqrt(disc);
    // Numerically stable pair (Numerical Recipes 5.6).
    double q = -0.5 * (b + std::copysign(sq, b));
    if (q != 0) roots[n++] = c / q;
    roots[n++] = q / a;
  }
  double best = nan;
  for (int i = 0; i < n; ++i)
    if (roots[i] >= lo && roots[i] <= hi && !(roots[i] >= best)) best = roots[i];
  return best;
}

double bilinear_patch_hit(double d00, double d10, double d01, double d11, double x, double y,
                          double z, double dx, double dy, double dz, double span) {
  // Bilinear D(x, y) = d00 + A x + B y + C x y; g(s) = ray depth - D along the segment.
  const double A = d10 - d00, B = d01 - d00, C = d00 - d10 - d01 + d11;
  const double qa = -C * dx * dy;
  const double qb = dz - A * dx - B * dy - C * (x * dy + y * dx);
  const double qc = z - d00 - A * x - B * y - C * x * y;
  if (qc >= 0) return 0.0;  // already at or below the patch where the segment starts
  return smallest_root_in(qa, qb, qc, 0.0, span);
}

ReferenceHit intersect_heightfield(const ReliefMap& map, const glm::dvec3& origin,
                                   const glm::dvec3& direction, double t_max) {
  ReferenceHit result;
  const int w = map.width, h = map.height;
  // Work in texel-centre coordinates: X = u * w - 0.5, so texel centres sit on integers and
  // cell (i, j) = [i, i+1] x [j, j+1] holds one bilinear patch.
  const double X0 = origin.x * w - 0.5, Y0 = origin.y * h - 0.5;
  const double dX = direction.x * w, dY = direction.y * h;
  const double z0 = origin.z, dz = direction.z;

  walk_grid_2d(X0, Y0, dX, dY, 0.0, t_max, [&](long i, long j, double t_enter, double t_exit) {
    ++result.cells;
    const int xi = static_cast<int>(((i % w) + w) % w), yj = static_cast<int>(((j % h) + h) % h);
    const double s = bilinear_patch_hit(
        map.depth_texel(xi, yj), map.depth_texel(xi + 1, yj), map.depth_texel(xi, yj + 1),
        map.depth_texel(xi + 1, yj + 1), X0 + dX * t_enter - double(i),
        Y0 + dY * t_enter - double(j), z0 + dz * t_enter, dX, dY, dz, t_exit - t_enter);
    if (std::isnan(s)) return false;
    const double t_hit = t_enter + s;
    result.hit = true;
    result.t = t_hit;
    result.uv = glm::dvec2(origin.x + direction.x * t_hit, origin.y + direction.y * t_hit);
    result.depth = z0 + dz * t_hit;
    return true;
  });
  return result;
}

ReferenceHit intersect_texel_columns(const ReliefMap& map, const glm::dvec3& origin,
                                     const glm::dvec3& direction, double t_max) {
  ReferenceHit result;
  const int w = map.width, h = map.height;
  // Texel coordinates X = u * w: cell (i, j) is texel (i, j), one column of constant depth.
  walk_grid_2d(origin.x * w, origin.y * h, direction.x * w, direction.y * h, 0.0, t_max,
               [&](long i, long j, double t_enter, double t_exit) {
                 ++result.cells;
                 const double d = map.depth_texel(int(((i % w) + w) % w), int(((j % h) + h) % h));
                 const double z_exit = origin.z + direction.z * t_exit;
                 if (z_exit < d) return false;
                 const double t_hit = std::max(t_enter, (d - origin.z) / direction.z);
                 result.hit = true;
                 result.t = t_hit;
                 result.uv = glm::dvec2(origin + direction * t_hit);
                 result.depth = origin.z + direction.z * t_hit;
                 return true;
               });
  return result;
}

}  // namespace rl
