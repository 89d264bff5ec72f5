#include "truth/displaced_truth.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/elapsed.h"
#include "core/embree_util.h"
#include "relief/heightfield_reference.h"
#include "relief/meta_relief.h"
#include "truth/meta_relief_truth.h"
#include "truth/min_pyramid.h"

namespace rl {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kMaxChords = 1 << 16;      // per walk: a guard, never reached on a sane base
constexpr int kMaxEntries = 256;         // sheet entries per ray, likewise
constexpr double kFirstStep = 4;         // the first chord's length, texels
constexpr double kFirstShadowStep = 16;  // a shadow or hemisphere ray's first chord, texels

// The least depth of a map (repeating, `tiling` times per unit of uv) over the bilinear cells
// that reach into [lo, hi], padded by a texel.
double least_texel(const MinPyramid& pyramid, double tiling, const glm::dvec2& lo,
                   const glm::dvec2& hi) {
  const double sx = tiling * pyramid.width(), sy = tiling * pyramid.height();
  return pyramid.least(long(std::floor(lo.x * sx - 0.5)) - 1, long(std::floor(hi.x * sx - 0.5)) + 2,
                       long(std::floor(lo.y * sy - 0.5)) - 1,
                       long(std::floor(hi.y * sy - 0.5)) + 2);
}

// The largest depth step between neighbouring texels of a plain map (wrapping).
double steepest_step(const ReliefMap& map) {
  double steepest = 0;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      const double here = map.depth_texel(x, y);
      steepest = std::max({steepest, std::abs(map.depth_texel((x + 1) % map.width, y) - here),
                           std::abs(map.depth_texel(x, (y + 1) % map.height) - here)});
    }
  return steepest;
}

// Per texel of the finest grid (`finest` texels per unit of uv): a meta-relief's layers add
// their shares of their own steps, each spread over its texels' share of the finest.
double steepest_step(const ReliefMap& map, double finest) {
  if (!map.meta) return steepest_step(map);
  double steepest = 0;
  for (size_t i = 0; i < map.meta->layers().size(); ++i) {
    const MetaLayer& layer = map.meta->layers()[i];
    const double texels = layer.tiling * std::max(layer.map.width, layer.map.height);
    steepest +=
        map.meta->depth_share(i) * steepest_step(layer.map) * std::min(1.0, texels / finest);
  }
  return steepest;
}

PrismPoint mix(const PrismPoint& a, const PrismPoint& b, double f) {
  return {a.triangle, a.b1 + (b.b1 - a.b1) * f, a.b2 + (b.b2 - a.b2) * f, a.s + (b.s - a.s) * f};
}

// Where the chord a-b leaves its triangle: the fraction (1: it does not) and the edge (the
// barycentric that reaches zero first). A point within rounding of an edge counts as inside,
// so a ray along an edge (a view down the normals) does not hop to and fro across it.
double exit_fraction(const PrismPoint& a, const PrismPoint& b, int& edge) {
  constexpr double kSlack = 1e-9;
  const double from[3] = {1 - a.b1 - a.b2, a.b1, a.b2}, to[3] = {1 - b.b1 - b.b2, b.b1, b.b2};
  double fraction = 1;
  edge = -1;
  for (int e = 0; e < 3; ++e) {
    if (to[e] >= -kSlack) continue;
    const double f = from[e] > 0 ? from[e] / (from[e] - to[e]) : 0.0;
    if (f < fraction || edge < 0) {
      fraction = std::min(fraction, f);
      edge = e;
    }
  }
  return fraction;
}

}  // namespace

struct DisplacedTruth::Chord {
  double t0, t1;
  PrismPoint a, b;  // in one prism
};

DisplacedTruth::DisplacedTruth(const BaseMesh& base, const ReliefMap& map, double depth,
                               double texels_per_sheet_edge, size_t max_sheet_triangles)
    : depth_(depth) {
  const auto start = std::chrono::steady_clock::now();
  glm::dvec2 texels(map.width, map.height);
  map_.meta = map.meta;  // surface_depth() then reads the layers' combination
  if (map.meta) {
    meta_ = std::make_unique<MetaReliefTruth>(map.meta);
    texels = glm::dvec2(map.meta->finest_texels());
  } else {
    map_.width = map.width;
    map_.height = map.height;
    map_.relief = map.relief;
  }
  max_slope_ = steepest_step(map, std::max(texels.x, texels.y));
  if (map.meta)
    for (const MetaLayer& layer : map.meta->layers()) pyramids_.emplace_back(layer.map);
  else
    pyramids_.emplace_back(map);
  prisms_ = std::make_unique<BasePrisms>(base, texels);
  sheets_ = std::make_unique<ShellSheets>(
      *prisms_, [this](const glm::dvec2& lo, const glm::dvec2& hi) { return least_depth(lo, hi); },
      depth, texels_per_sheet_edge, max_sheet_triangles);
  build_ms_ = ms_since(start);
}

DisplacedTruth::~DisplacedTruth() = default;

double DisplacedTruth::least_depth(const glm::dvec2& lo, const glm::dvec2& hi) const {
  if (!meta_) return least_texel(pyramids_[0], 1.0, lo, hi);
  // Eq. 2 is a sum with non-negative shares: its least is at least the shares' least parts.
  const MetaRelief& meta = *map_.meta;
  double least = 0;
  for (size_t i = 0; i < meta.layers().size(); ++i)
    least += meta.depth_share(i) * least_texel(pyramids_[i], meta.layers()[i].tiling, lo, hi);
  return least;
}

glm::dvec3 DisplacedTruth::texture_point(const PrismPoint& p) const {
  return glm::dvec3(prisms_->uv(p.triangle, p.b1, p.b2), p.s / depth_);
}

double DisplacedTruth::chord_crossing(const glm::dvec3& a, const glm::dvec3& b) const {
  ++chords_;
  if (meta_) return meta_->first_hit(a, b - a, 0.0, 1.0);
  const ReferenceHit r = intersect_heightfield(map_, a, b - a, 1.0);
  return r.hit ? r.t : kNaN;
}

double DisplacedTruth::chord_deviation(const glm::dvec3& o, const glm::dvec3& d,
                                       const PrismPoint& a, const PrismPoint& b) const {
  double worst = 0;
  for (double f : {0.25, 0.5, 0.75}) {
    const PrismPoint m = mix(a, b, f);
    const glm::dvec3 w = prisms_->point(m.triangle, m.b1, m.b2, m.s) - o;
    worst = std::max(worst, glm::length(w - glm::dot(w, d) * d));
  }
  // Between the samples the stray of a smooth chord can only grow by a fraction of itself.
  return 1.25 * worst;
}

DisplacedHit DisplacedTruth::hit_at(const glm::dvec3& o, const glm::dvec3& d, const PrismPoint& p,
                                    double off_ray) const {
  DisplacedHit h;
  const unsigned t = p.triangle;
  h.hit = true;
  h.position = prisms_->point(t, p.b1, p.b2, p.s);
  h.t = glm::dot(h.position - o, d);
  h.uv = prisms_->uv(t, p.b1, p.b2);
  h.normal = prisms_->unit_normal(t, p.b1, p.b2);
  prisms_->frame(t, p.b1, p.b2, h.tangent, h.bitangent);
  h.off_ray = off_ray;
  h.base_triangle = int(t);
  // The relief's own normal: central differences a thousandth of a texel wide.
  const double step = 1e-3 * prisms_->texel_world(t);
  auto surface = [&](double b1, double b2) {
    const glm::dvec2 uv = prisms_->uv(t, b1, b2);
    return prisms_->point(t, b1, b2, depth_ * map_.surface_depth(uv.x, uv.y));
  };
  const glm::dvec3 e1 = prisms_->point(t, 1, 0, 0) - prisms_->point(t, 0, 0, 0);
  const glm::dvec3 e2 = prisms_->point(t, 0, 1, 0) - prisms_->point(t, 0, 0, 0);
  const double db1 = step / std::max(glm::length(e1), 1e-300);
  const double db2 = step / std::max(glm::length(e2), 1e-300);
  const glm::dvec3 n = glm::cross(surface(p.b1 + db1, p.b2) - surface(p.b1 - db1, p.b2),
                                  surface(p.b1, p.b2 + db2) - surface(p.b1, p.b2 - db2));
  if (glm::length(n) > 0)
    h.geometric_normal = glm::dot(n, d) > 0 ? -glm::normalize(n) : glm::normalize(n);
  return h;
}

// The first hit on the chord's stretch of the ray. The chord lies within `deviation` of the ray,
// so where the chord pushed down by lift(deviation) passes above the relief, so does the ray;
// otherwise the chord is halved (its stray quarters) until it lies within kHitDeviation texel
// of the ray, and there the chord's own crossing is the answer.
DisplacedHit DisplacedTruth::resolve(const glm::dvec3& o, const glm::dvec3& d, const Chord& c,
                                     double deviation, int level) const {
  const double texel = prisms_->texel_world(c.a.triangle);
  const glm::dvec3 ta = texture_point(c.a), tb = texture_point(c.b);
  const glm::dvec3 down(0, 0, lift(deviation, texel));
  if (std::isnan(chord_crossing(ta + down, tb + down))) return {};
  const double tm = 0.5 * (c.t0 + c.t1);
  PrismPoint m;
  if (deviation <= kHitDeviation * texel || level >= 48 || !(tm > c.t0 && tm < c.t1) ||
      !prisms_->locate(o + tm * d, c.a.triangle, m)) {
    const double crossing = chord_crossing(ta, tb);
    return std::isnan(crossing) ? DisplacedHit{} : hit_at(o, d, mix(c.a, c.b, crossing), deviation);
  }
  for (const Chord& half : {Chord{c.t0, tm, c.a, m}, Chord{tm, c.t1, m, c.b}}) {
    const DisplacedHit h = resolve(o, d, half, chord_deviation(o, d, half.a, half.b), level + 1);
    if (h.hit) return h;
  }
  return {};
}

// How far down (depth units) a chord that strays `deviation` (world) from the ray is pushed so
// that it meets the relief wherever the ray does: the stray along the fibre, and across it times
// the map's steepest slope.
double DisplacedTruth::lift(double deviation, double texel_world) const {
  return deviation / depth_ + max_slope_ * deviation / texel_world;
}

// Where the ray crosses edge `edge` of the prism (the barycentric opposite falls to 0) between
// a (at t_in, inside) and b (at t_out, past it): the Illinois variant of regula falsi on that
// barycentric, which is smooth along the ray within the prism. `at`: the prism point there.
double DisplacedTruth::edge_crossing(const glm::dvec3& o, const glm::dvec3& d, int edge,
                                     const PrismPoint& a, double t_in, const PrismPoint& b,
                                     double t_out, PrismPoint& at) const {
  auto barycentric = [&](const PrismPoint& p) {
    return edge == 0 ? 1 - p.b1 - p.b2 : (edge == 1 ? p.b1 : p.b2);
  };
  double lo = t_in, hi = t_out, f_lo = barycentric(a), f_hi = barycentric(b);
  at = b;
  int side = 0;
  for (int iteration = 0; iteration < 32 && f_lo > 0 && f_hi < 0; ++iteration) {
    const double t = lo + (hi - lo) * f_lo / (f_lo - f_hi);
    PrismPoint p;
    if (!(t > lo && t < hi) || !prisms_->locate(o + t * d, a.triangle, p)) break;
    at = p;
    const double f = barycentric(p);
    if (std::abs(f) <= 1e-12) return t;
    if (f > 0) {
      lo = t, f_lo = f;
      if (side == 1) f_hi *= 0.5;  // the same end kept twice: halve the other's weight
      side = 1;
    } else {
      hi = t, f_hi = f;
      if (side == -1) f_lo *= 0.5;
      side = -1;
    }
  }
  return glm::dot(prisms_->point(at.triangle, at.b1, at.b2, at.s) - o, d);
}

DisplacedHit DisplacedTruth::walk(const glm::dvec3& o, const glm::dvec3& d, double t_min,
                                  double t_max, unsigned from, bool any_hit, double& resume) const {
  resume = kNaN;
  double t = t_min;
  PrismPoint a;
  if (!prisms_->locate(o + t * d, from, a)) {
    resume = t;
    return {};
  }
  // A shadow or hemisphere ray is short and starts on the relief: a longer first chord.
  double step = (any_hit ? kFirstShadowStep : kFirstStep) * prisms_->texel_world(a.triangle);
  int came_from = -1;  // the prism the walk last hopped from, and where
  double hop_t = kNaN;
  for (int chord = 0; chord < kMaxChords; ++chord) {
    const double texel = prisms_->texel_world(a.triangle);
    const double t1 = std::min(t + step, t_max);
    PrismPoint b;
    const bool located = prisms_->locate(o + t1 * d, a.triangle, b);
    int edge = -1;
    double fraction = located ? exit_fraction(a, b, edge) : 0.0;
    // Where the base bends faster than the shell is deep, prisms fold and a point may lie in
    // no prism: each sends it to the other. The walk then follows this prism's extension.
    if (located && fraction == 0 && t == hop_t && prisms_->neighbour(a.triangle, edge) == came_from)
      fraction = 1;
    // A chord that leaves the prism ends where the ray itself crosses the edge, so that it
    // hands over at the same point however long it was (a uv seam may leave a cliff there).
    PrismPoint e = fraction > 0 ? b : a;
    double t_e = fraction > 0 ? t1 : t;
    if (located && fraction > 0 && fraction < 1) t_e = edge_crossing(o, d, edge, a, t, b, t1, e);
    const double target = kWalkDeviation * texel;
    const double deviation = located && fraction > 0 ? chord_deviation(o, d, a, e) : 0.0;
    // A chord strays from the ray as its length squared: the next length aims just inside.
    const double chord_length = t_e - t;
    const double fitting =
        deviation > 0 ? 0.9 * chord_length * std::sqrt(target / deviation) : 4 * step;
    if (!located || deviation > target) {
      if (step <= 1e-6 * texel) break;
      step = located ? std::clamp(fitting, 0.1 * step, 0.5 * step) : 0.5 * step;
      continue;
    }
    // (A chord of no length -- the start already past an edge -- only hands over.)
    if (fraction > 0 && any_hit) {
      if (!std::isnan(chord_crossing(texture_point(a), texture_point(e)))) {
        DisplacedHit h;  // a shadow ray needs only that it is met, to the walk's stray
        h.hit = true;
        return h;
      }
    } else if (fraction > 0) {
      const DisplacedHit h = resolve(o, d, Chord{t, t_e, a, e}, deviation, 0);
      if (h.hit) return h;
    }
    t = t_e;
    if (t >= t_max) return {};
    if (fraction < 1) {
      const int next = prisms_->neighbour(a.triangle, edge);
      came_from = int(a.triangle);
      hop_t = t;
      if (next < 0 || !prisms_->locate(o + t * d, unsigned(next), a)) {
        resume = t;
        return {};
      }
    } else {
      a = b;
    }
    if (sheets_->outside(o + t * d, a)) {
      resume = t;
      return {};
    }
    // Longer than its prism is wide, a chord is clipped anyway (and its far end hard to locate).
    step = std::min({std::max(fitting, 0.5 * step), 4 * step, prisms_->extent(a.triangle)});
  }
  resume = t;
  return {};
}

DisplacedHit DisplacedTruth::first_hit(const glm::dvec3& o, const glm::dvec3& d, double t_min,
                                       double t_max, int from, bool any_hit) const {
  double t = t_min;
  if (from >= 0 && prisms_->usable(unsigned(from))) {
    double resume;
    const DisplacedHit h = walk(o, d, t, t_max, unsigned(from), any_hit, resume);
    if (h.hit || std::isnan(resume)) return h;
    t = resume;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (int entry = 0; entry < kMaxEntries && t < t_max; ++entry) {
    ++embree_queries_;
    RTCRayHit rh = embree_ray(o, d, t, t_max);
    rtcIntersect1(sheets_->scene(), &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};
    const double at = rh.ray.tfar;
    // Past the sheet triangle met, by more than Embree's float rounding of the ray.
    const double past = std::max(at, t) * (1 + 1e-6) + 1e-7;
    if (!sheets_->entering(rh.hit.primID, d)) {
      t = past;
      continue;
    }
    double resume;
    const DisplacedHit h =
        walk(o, d, at, t_max, sheets_->base_triangle(rh.hit.primID), any_hit, resume);
    if (h.hit || std::isnan(resume)) return h;
    t = std::max(resume, past);
  }
  return {};
}

DisplacedHit DisplacedTruth::intersect(const glm::dvec3& origin, const glm::dvec3& direction,
                                       double t_max) const {
  ++primary_rays_;
  return first_hit(origin, direction, 0.0, t_max, -1, false);
}

bool DisplacedTruth::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                              double t_max, int from) const {
  ++shadow_rays_;
  return first_hit(origin, direction, t_min, t_max, from, true).hit;
}

}  // namespace rl
