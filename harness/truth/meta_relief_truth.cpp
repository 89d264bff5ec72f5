#include "truth/meta_relief_truth.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "relief/heightfield_reference.h"

namespace rl {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// One layer's DDA along one axis of its texel-centre grid: X(t) = x0 + dx t, cells [c, c + 1).
struct AxisWalk {
  double x0 = 0, dx = 0;
  long cell = 0;
  int step = 0;
  double next = kInf, delta = kInf;  // t of the next crease crossing, and between crossings

  void start(double origin, double slope, double t) {
    x0 = origin;
    dx = slope;
    const double x = x0 + dx * t;
    cell = static_cast<long>(std::floor(x));
    step = dx > 0 ? 1 : (dx < 0 ? -1 : 0);
    delta = step ? 1.0 / std::abs(dx) : kInf;
    next = step > 0 ? t + (cell + 1 - x) / dx : (step < 0 ? t + (x - cell) / -dx : kInf);
  }
  void advance() {
    cell += step;
    next += delta;
  }
};

struct LayerWalk {
  AxisWalk x, y;
};

}  // namespace

MetaReliefTruth::MetaReliefTruth(std::shared_ptr<const MetaRelief> meta) : meta_(std::move(meta)) {}

double MetaReliefTruth::first_hit(const glm::dvec3& o, const glm::dvec3& d, double t_min,
                                  double t_max, long* cells) const {
  const auto& layers = meta_->layers();
  std::vector<LayerWalk> walks(layers.size());
  double crossings_per_t = 0;
  for (size_t i = 0; i < layers.size(); ++i) {
    // Texel-centre coordinates of layer i: X = u * tiling * width - 0.5, texel centres on
    // integers, so cell (I, J) holds one bilinear patch.
    const ReliefMap& m = layers[i].map;
    const double sx = layers[i].tiling * m.width, sy = layers[i].tiling * m.height;
    walks[i].x.start(o.x * sx - 0.5, d.x * sx, t_min);
    walks[i].y.start(o.y * sy - 0.5, d.y * sy, t_min);
    crossings_per_t += std::abs(d.x * sx) + std::abs(d.y * sy);
  }
  // Bounded: every step crosses at least one crease, and there are at most this many.
  const long max_steps =
      static_cast<long>(std::min(crossings_per_t * std::max(0.0, t_max - t_min), 1e9)) +
      4 * long(layers.size()) + 4;
  double t_enter = t_min;
  for (long n = 0; n < max_steps && t_enter <= t_max; ++n) {
    if (cells) ++*cells;
    double t_exit = t_max;
    for (const LayerWalk& w : walks) t_exit = std::min({t_exit, w.x.next, w.y.next});
    // f(tau) = ray depth - surface depth at t = t_enter + tau, a quadratic in this union cell.
    double qa = 0, qb = d.z, qc = o.z + d.z * t_enter;
    for (size_t i = 0; i < layers.size(); ++i) {
      const LayerWalk& w = walks[i];
      const ReliefMap& m = layers[i].map;
      const int xi = int(w.x.cell % m.width), yj = int(w.y.cell % m.height);
      const double d00 = m.depth_texel(xi, yj), d10 = m.depth_texel(xi + 1, yj);
      const double d01 = m.depth_texel(xi, yj + 1), d11 = m.depth_texel(xi + 1, yj + 1);
      const double A = d10 - d00, B = d01 - d00, C = d00 - d10 - d01 + d11;
      // Local coordinates from the cell's entry (no cancellation far along the ray).
      const double px = w.x.x0 + w.x.dx * t_enter - double(w.x.cell);
      const double py = w.y.x0 + w.y.dx * t_enter - double(w.y.cell);
      const double s = meta_->depth_share(i);
      qa -= s * C * w.x.dx * w.y.dx;
      qb -= s * (A * w.x.dx + B * w.y.dx + C * (px * w.y.dx + py * w.x.dx));
      qc -= s * (d00 + A * px + B * py + C * px * py);
    }
    const double span = t_exit - t_enter;
    const double tau = qc >= 0 ? 0.0 : smallest_root_in(qa, qb, qc, 0.0, span);
    if (!std::isnan(tau)) return t_enter + tau;
    if (t_exit >= t_max) break;
    for (LayerWalk& w : walks) {
      if (w.x.next <= t_exit) w.x.advance();
      if (w.y.next <= t_exit) w.y.advance();
    }
    t_enter = t_exit;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

TruthHit MetaReliefTruth::intersect(const glm::dvec3& origin, const glm::dvec3& direction,
                                    double t_min, double t_max) const {
  ++primary_rays_;
  TruthHit hit;
  const double t = first_hit(origin, direction, t_min, t_max);
  if (std::isnan(t)) return hit;
  hit.hit = true;
  hit.t = t;
  hit.point = origin + direction * t;
  return hit;
}

bool MetaReliefTruth::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                               double t_max) const {
  ++shadow_rays_;
  return !std::isnan(first_hit(origin, direction, t_min, t_max));
}

}  // namespace rl
