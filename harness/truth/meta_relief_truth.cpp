#include "truth/meta_relief_truth.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/wrap.h"
#include "relief/heightfield_reference.h"

namespace rl {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// One layer's DDA along one axis of its texel-centre grid: X(t) = x0 + dx t, cells [c, c + 1).
// `wrapped` is the cell taken into [0, n), kept as the walk steps: no division per cell (two
// integer remainders per axis and step were a fifth of an AO ray's time).
struct AxisWalk {
  double x0 = 0, dx = 0;
  long cell = 0;
  int wrapped = 0, n = 1;
  int step = 0;
  double next = kInf, delta = kInf;  // t of the next crease crossing, and between crossings

  void start(double origin, double slope, double t, int cells) {
    x0 = origin;
    dx = slope;
    n = cells;
    const double x = x0 + dx * t;
    cell = static_cast<long>(std::floor(x));
    wrapped = wrap_index(cell, n);
    step = dx > 0 ? 1 : (dx < 0 ? -1 : 0);
    delta = step ? 1.0 / std::abs(dx) : kInf;
    next = step > 0 ? t + (cell + 1 - x) / dx : (step < 0 ? t + (x - cell) / -dx : kInf);
  }
  void advance() {
    cell += step;
    wrapped += step;
    if (wrapped == n) wrapped = 0;
    if (wrapped < 0) wrapped = n - 1;
    next += delta;
  }
};

// One layer's walk and the bilinear patch of the cell it is in:
// D(px, py) = d00 + A px + B py + C px py, with px, py from the cell's corner.
struct LayerWalk {
  AxisWalk x, y;
  double share = 0;                                 // of the depth (Eq. 2)
  double d00 = 0, A = 0, B = 0, C = 0, lowest = 0;  // lowest: the shallowest corner

  // `depth`: the layer's depths, row-major, `w` x `h`.
  void load_patch(const float* depth, int w, int h) {
    // The cell's corners, wrapping like GL_REPEAT (the walk's cells may be negative).
    const int x0 = x.wrapped, y0 = y.wrapped;
    const int x1 = x0 + 1 == w ? 0 : x0 + 1, y1 = y0 + 1 == h ? 0 : y0 + 1;
    const float* row0 = depth + size_t(y0) * w;
    const float* row1 = depth + size_t(y1) * w;
    d00 = row0[x0];
    const double d10 = row0[x1], d01 = row1[x0], d11 = row1[x1];
    A = d10 - d00;
    B = d01 - d00;
    C = d00 - d10 - d01 + d11;
    lowest = std::min({d00, d10, d01, d11});
  }
  // Subtracts this layer's share of the surface depth at t = t_enter + tau from the quadratic
  // qa tau^2 + qb tau + qc. Local coordinates from the cell's corner at the cell's entry (no
  // cancellation far along the ray).
  void add_patch(double t_enter, double& qa, double& qb, double& qc) const {
    const double px = x.x0 + x.dx * t_enter - double(x.cell);
    const double py = y.x0 + y.dx * t_enter - double(y.cell);
    qa -= share * C * x.dx * y.dx;
    qb -= share * (A * x.dx + B * y.dx + C * (px * y.dx + py * x.dx));
    qc -= share * (d00 + A * px + B * py + C * px * py);
  }
};

}  // namespace

MetaReliefTruth::MetaReliefTruth(std::shared_ptr<const MetaRelief> meta) : meta_(std::move(meta)) {
  // Each layer's depths alone, 4 bytes a texel: the walk reads four per cell it enters, and
  // from the maps' 16-byte texels those reads missed the cache on the finer layers.
  for (const MetaLayer& layer : meta_->layers()) depths_.push_back(layer.map.depths());
}

double MetaReliefTruth::first_hit(const glm::dvec3& o, const glm::dvec3& d, double t_min,
                                  double t_max, long* cells) const {
  const auto& layers = meta_->layers();
  // Most meta-reliefs have a few layers: their walks live on the stack.
  constexpr size_t kInline = 4;
  LayerWalk inline_walks[kInline];
  std::vector<LayerWalk> many(layers.size() > kInline ? layers.size() : 0);
  LayerWalk* walks = layers.size() > kInline ? many.data() : inline_walks;
  double crossings_per_t = 0;
  for (size_t i = 0; i < layers.size(); ++i) {
    // Texel-centre coordinates of layer i: X = u * tiling * width - 0.5, texel centres on
    // integers, so cell (I, J) holds one bilinear patch.
    const ReliefMap& m = layers[i].map;
    const double sx = layers[i].tiling * m.width, sy = layers[i].tiling * m.height;
    walks[i].x.start(o.x * sx - 0.5, d.x * sx, t_min, m.width);
    walks[i].y.start(o.y * sy - 0.5, d.y * sy, t_min, m.height);
    walks[i].share = meta_->depth_share(i);
    walks[i].load_patch(depths_[i].data(), m.width, m.height);
    crossings_per_t += std::abs(d.x * sx) + std::abs(d.y * sy);
  }
  // Bounded: every step crosses at least one crease, and there are at most this many.
  const long max_steps =
      static_cast<long>(std::min(crossings_per_t * std::max(0.0, t_max - t_min), 1e9)) +
      4 * long(layers.size()) + 4;
  double t_enter = t_min;
  for (long n = 0; n < max_steps && t_enter <= t_max; ++n) {
    if (cells) ++*cells;
    double t_exit = t_max, shallowest = 0;
    for (size_t i = 0; i < layers.size(); ++i) {
      t_exit = std::min({t_exit, walks[i].x.next, walks[i].y.next});
      shallowest += walks[i].share * walks[i].lowest;
    }
    // The patch is nowhere shallower than its layers' shallowest corners: a ray above that
    // all through the cell cannot meet it (the margin covers the quadratic's rounding).
    const double deepest = std::max(o.z + d.z * t_enter, o.z + d.z * t_exit);
    if (!(deepest < shallowest - 1e-12)) {
      // f(tau) = ray depth - surface depth at t = t_enter + tau, a quadratic in this cell.
      double qa = 0, qb = d.z, qc = o.z + d.z * t_enter;
      for (size_t i = 0; i < layers.size(); ++i) walks[i].add_patch(t_enter, qa, qb, qc);
      const double tau = qc >= 0 ? 0.0 : smallest_root_in(qa, qb, qc, 0.0, t_exit - t_enter);
      if (!std::isnan(tau)) return t_enter + tau;
    }
    if (t_exit >= t_max) break;
    for (size_t i = 0; i < layers.size(); ++i) {
      bool moved = false;
      if (walks[i].x.next <= t_exit) walks[i].x.advance(), moved = true;
      if (walks[i].y.next <= t_exit) walks[i].y.advance(), moved = true;
      if (moved) walks[i].load_patch(depths_[i].data(), layers[i].map.width, layers[i].map.height);
    }
    t_enter = t_exit;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

TruthHit MetaReliefTruth::intersect(const glm::dvec3& origin, const glm::dvec3& direction,
                                    double t_min, double t_max) const {
  ++primary_rays_;
  return hit_at(origin, direction, first_hit(origin, direction, t_min, t_max));
}

bool MetaReliefTruth::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                               double t_max) const {
  ++shadow_rays_;
  return !std::isnan(first_hit(origin, direction, t_min, t_max));
}

}  // namespace rl
