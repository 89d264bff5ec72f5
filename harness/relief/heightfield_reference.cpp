#include "relief/heightfield_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rl {
namespace {

// Smallest root of a t^2 + b t + c = 0 in [lo, hi], or NaN.
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

}  // namespace

ReferenceHit intersect_heightfield(const ReliefMap& map, const glm::dvec3& origin,
                                   const glm::dvec3& direction, double t_max) {
  ReferenceHit result;
  const int w = map.width, h = map.height;
  // Work in texel-centre coordinates: X = u * w - 0.5, so texel centres sit on integers and
  // cell (i, j) = [i, i+1] x [j, j+1] holds one bilinear patch.
  const double X0 = origin.x * w - 0.5, Y0 = origin.y * h - 0.5;
  const double dX = direction.x * w, dY = direction.y * h;
  const double z0 = origin.z, dz = direction.z;

  long i = static_cast<long>(std::floor(X0)), j = static_cast<long>(std::floor(Y0));
  const int step_i = dX > 0 ? 1 : (dX < 0 ? -1 : 0);
  const int step_j = dY > 0 ? 1 : (dY < 0 ? -1 : 0);
  const double inf = std::numeric_limits<double>::infinity();
  const double delta_i = step_i ? 1.0 / std::abs(dX) : inf;
  const double delta_j = step_j ? 1.0 / std::abs(dY) : inf;
  double next_i = step_i > 0 ? (i + 1 - X0) / dX : (step_i < 0 ? (X0 - i) / -dX : inf);
  double next_j = step_j > 0 ? (j + 1 - Y0) / dY : (step_j < 0 ? (Y0 - j) / -dY : inf);

  double t_enter = 0;
  // Bounded walk: a ray crosses at most |dX| + |dY| cell boundaries per unit t.
  const long max_cells = static_cast<long>((std::abs(dX) + std::abs(dY)) * t_max) + 4;
  for (long n = 0; n <= max_cells && t_enter <= t_max; ++n) {
    const double t_exit = std::min({next_i, next_j, t_max});
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
    double t_hit = std::numeric_limits<double>::quiet_NaN();
    if (f_enter >= 0) {
      t_hit = t_enter;
    } else {
      t_hit = smallest_root_in(qa, qb, qc, t_enter, t_exit);
    }
    if (!std::isnan(t_hit)) {
      result.hit = true;
      result.t = t_hit;
      result.uv = glm::dvec2(origin.x + direction.x * t_hit, origin.y + direction.y * t_hit);
      result.depth = z0 + dz * t_hit;
      return result;
    }
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
  return result;
}

}  // namespace rl
