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
    const double d00 = map.depth_texel(xi, yj), d10 = map.depth_texel(xi + 1, yj);
    const double d01 = map.depth_texel(xi, yj + 1), d11 = map.depth_texel(xi + 1, yj + 1);
    // Local coordinates in the cell: fx = (X0 - i) + dX t, fy = (Y0 - j) + dY t.
    const double px = X0 - i, py = Y0 - j;
    // Bilinear D(fx, fy) = d00 + (d10-d00) fx + (d01-d00) fy + (d00-d10-d01+d11) fx fy.
    const double A = d10 - d00, B = d01 - d00, C = d00 - d10 - d01 + d11;
    // f(t) = ray depth - surface depth = z0 + dz t - D(px + dX t, py + dY t).
    const double qa = -C * dX * dY;
    const double qb = dz - A * dX - B * dY - C * (px * dY + py * dX);
    const double qc = z0 - d00 - A * px - B * py - C * px * py;
    const double f_enter = qa * t_enter * t_enter + qb * t_enter + qc;
    const double t_hit = f_enter >= 0 ? t_enter : smallest_root_in(qa, qb, qc, t_enter, t_exit);
    if (std::isnan(t_hit)) return false;
    result.hit = true;
    result.t = t_hit;
    result.uv = glm::dvec2(origin.x + direction.x * t_hit, origin.y + direction.y * t_hit);
    result.depth = z0 + dz * t_hit;
    return true;
  });
  return result;
}

}  // namespace rl
