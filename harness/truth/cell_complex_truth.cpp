#include "truth/cell_complex_truth.h"

#include <algorithm>
#include <cmath>

namespace rl {

CellComplexTruth::CellComplexTruth(std::shared_ptr<const CellComplex> cells)
    : cells_(std::move(cells)) {
  step_ = 0.25 / (double(cells_->grid()) * cells_->resolution());
}

TruthHit CellComplexTruth::intersect(const glm::dvec3& o, const glm::dvec3& d, double t_min,
                                     double t_max) const {
  ++primary_rays_;
  return trace(o, d, t_min, t_max);
}

TruthHit CellComplexTruth::trace(const glm::dvec3& o, const glm::dvec3& d, double t_min,
                                 double t_max) const {
  TruthHit h;
  const double speed = glm::length(d);
  if (!(speed > 0)) return h;
  const CellComplex& cc = *cells_;
  const int n = cc.grid();
  const double dt = step_ / speed;
  // Past the end of a white cell along the ray (the next sample), or t + dt.
  auto next_t = [&](double t) {
    const glm::dvec3 g = (o + d * t) * double(n);
    glm::ivec3 c;
    for (int k = 0; k < 3; ++k) c[k] = std::clamp(int(std::floor(g[k])), 0, n - 1);
    for (int k = 0; k < 3; ++k)
      if (!(g[k] >= 0 && g[k] <= n)) return t + dt;  // outside the grid: plain steps
    if (cc.cell(c.x, c.y, c.z).state != CellState::White) return t + dt;
    double exit = 1e300;
    for (int k = 0; k < 3; ++k) {
      if (d[k] > 0) exit = std::min(exit, ((c[k] + 1.0) / n - o[k]) / d[k]);
      if (d[k] < 0) exit = std::min(exit, (double(c[k]) / n - o[k]) / d[k]);
    }
    return std::max(t + dt, exit + 1e-9 / speed);
  };
  double t_out = t_min;
  if (cc.encoded_inside(o + d * t_min)) {
    h.hit = true;
    h.t = t_min;
  } else {
    for (double t = next_t(t_min);; t = next_t(t)) {
      const double tc = std::min(t, t_max);
      if (cc.encoded_inside(o + d * tc)) {
        double a = t_out, b = tc;
        for (int i = 0; i < 60 && b - a > 1e-12 * std::max(1.0, b); ++i) {
          const double m = 0.5 * (a + b);
          (cc.encoded_inside(o + d * m) ? b : a) = m;
        }
        h.hit = true;
        h.t = b;
        break;
      }
      t_out = tc;
      if (tc >= t_max) return h;
    }
  }
  h.point = o + d * h.t;
  // Normal and colour of the face point just outside the hit (the grey cell it is in).
  const CellComplex::Lookup l = cc.lookup(o + d * t_out);
  const CellComplex::Lookup at = l.face_index >= 0 ? l : cc.lookup(h.point);
  h.has_normal = true;
  h.normal = at.face_index >= 0 ? cc.sample_normal(at.face_index, at.st) : -d / speed;
  if (at.face_index >= 0) {
    h.has_albedo = true;
    h.albedo = cc.sample_color(at.face_index, at.st);
  }
  return h;
}

bool CellComplexTruth::occluded(const glm::dvec3& o, const glm::dvec3& d, double t_min,
                                double t_max) const {
  ++shadow_rays_;
  return trace(o, d, t_min, t_max).hit;
}

}  // namespace rl
