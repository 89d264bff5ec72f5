#include "safety_radius.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include <glm/gtc/constants.hpp>

#include "core/parallel.h"
#include "core/precompute_cache.h"

namespace rl {

int SafetyRadii::zero_count() const {
  return int(std::count(radius.begin(), radius.end(), uint8_t(0)));
}

namespace {

// The scan of first_two_hit_distance over heights produced on demand by height(k), stopping
// at sample `limit`: the radius search only needs violations nearer than its current radius.
template <typename Height>
double scan_profile(Height&& height, int limit, double step, double error_allowed) {
  // A descending ray (height falling at any rate k >= 0) that is above the surface at 0 dips
  // below it at s1 and is above again at s2 > s1 exactly when, for the lowest such ray:
  // - h(s2) <= h(0): the chord from (0, h0) to (s2, h(s2)) passes below some h(s1), i.e. the
  //   largest slope from the start to an earlier point exceeds the slope to s2;
  // - h(s2) > h(0): a horizontal ray just above h(s2) passes below an earlier, higher h(s1).
  // A dip of at most error_allowed does not count (Figure 12's trade of error for speed).
  const double inf = std::numeric_limits<double>::infinity();
  const double h0 = height(0);
  double max_slope = -inf, max_h = -inf;
  for (int k = 1; k < limit; ++k) {
    const double s = k * step, hk = height(k);
    const double slope = (hk - h0) / s;
    if (hk <= h0) {
      if (max_slope > slope + 1e-12) return s;
    } else if (max_h > hk + 1e-12) {
      return s;
    }
    max_slope = std::max(max_slope, (hk - error_allowed - h0) / s);
    max_h = std::max(max_h, hk - error_allowed);
  }
  return inf;
}

}  // namespace

double first_two_hit_distance(const std::vector<double>& h, double step, double error_allowed) {
  return scan_profile([&](int k) { return h[size_t(k)]; }, int(h.size()), step, error_allowed);
}

namespace {

// Bilinear depth at texel-centre coordinates (x, y), wrapping like GL_REPEAT: the same value
// as ReliefMap::sample_depth, on a plain float array (this loop is the precompute's hot spot).
class DepthSampler {
 public:
  explicit DepthSampler(const ReliefMap& m) : w_(m.width), h_(m.height), d_(m.relief.size()) {
    for (size_t i = 0; i < d_.size(); ++i) d_[i] = m.relief[i].a;
  }
  double operator()(double x, double y) const {
    // Shift by whole tiles so the floor and the wrap see non-negative values; the floor of a
    // positive value is its truncation (no library call), and a texel inside the map needs no
    // division to wrap.
    x += 64.0 * w_;
    y += 64.0 * h_;
    const double fx0 = double(long(x)), fy0 = double(long(y));
    const double fx = x - fx0, fy = y - fy0;
    const long x0 = wrap(long(fx0) - 64 * w_, w_), y0 = wrap(long(fy0) - 64 * h_, h_);
    const long x1 = x0 + 1 == w_ ? 0 : x0 + 1, y1 = y0 + 1 == h_ ? 0 : y0 + 1;
    const float* r0 = &d_[size_t(y0) * w_];
    const float* r1 = &d_[size_t(y1) * w_];
    return (r0[x0] * (1 - fx) + r0[x1] * fx) * (1 - fy) + (r1[x0] * (1 - fx) + r1[x1] * fx) * fy;
  }

 private:
  static long wrap(long a, long n) {
    if (a >= 0 && a < n) return a;
    const long r = a % n;
    return r < 0 ? r + n : r;
  }
  long w_, h_;
  std::vector<float> d_;
};

// Heights (= -depth) of the map padded by `pad` texels of wrapped copies on every side, so the
// line sweep samples bilinearly without a modulo per sample; `transposed` swaps x and y, so
// that a sweep always runs along rows (contiguous memory) whatever its major axis.
class PaddedHeights {
 public:
  PaddedHeights(const ReliefMap& m, int pad, bool transposed)
      : w_(transposed ? m.height : m.width),
        h_(transposed ? m.width : m.height),
        pad_(pad),
        stride_(size_t(w_ + 2 * pad)) {
    data_.resize(stride_ * size_t(h_ + 2 * pad));
    for (int y = -pad; y < h_ + pad; ++y)
      for (int x = -pad; x < w_ + pad; ++x) {
        const int sx = ((x % w_) + w_) % w_, sy = ((y % h_) + h_) % h_;
        const size_t src = transposed ? m.index(sy, sx) : m.index(sx, sy);
        data_[size_t(y + pad) * stride_ + size_t(x + pad)] = -m.relief[src].a;
      }
  }
  int width() const { return w_; }
  int height() const { return h_; }
  // Bilinear height at texel-centre coordinates (x, y), both above -pad.
  float operator()(double x, double y) const {
    const double px = x + pad_, py = y + pad_;
    const long ix = long(px), iy = long(py);  // floor: both are positive
    const float fx = float(px - double(ix)), fy = float(py - double(iy));
    const float* r0 = &data_[size_t(iy) * stride_ + size_t(ix)];
    const float* r1 = r0 + stride_;
    const float top = r0[0] + (r0[1] - r0[0]) * fx, bottom = r1[0] + (r1[1] - r1[0]) * fx;
    return top + (bottom - top) * fy;
  }

 private:
  int w_, h_, pad_;
  size_t stride_;
  std::vector<float> data_;
};

}  // namespace

// Height (depth units) within which a ray counts as touching, not entering, the surface: ten
// times the rounding of float heights in [-1, 0], a 4000th of an 8-bit depth step.
constexpr double kTouch = 1e-6;

void first_unblocked_violations(const std::vector<float>& h, double step, double error_allowed,
                                std::vector<int>& hull, std::vector<int>& first) {
  const int n = int(h.size());
  // by_horizon[t]: the first sample whose horizon is sample t.
  first.assign(size_t(n), n);
  std::vector<int>& by_horizon = first;
  hull.clear();
  // Is the hull's top on, under, or within kTouch above the edge (second, k)? Such a vertex is
  // a collinear tie: a ray along the edge touches it without dipping in. The tolerance keeps
  // float rounding on planar slopes (a pyramid's face, sampled by bilinear lerps) from
  // turning exact ties into dips of 1e-8 that zeroed the radii of whole faces.
  auto below_new_edge = [&](int k) {
    const int i = hull[hull.size() - 2], j = hull.back();
    return double(j - i) * (double(h[size_t(k)]) - h[size_t(i)]) -
               (double(h[size_t(j)]) - h[size_t(i)]) * double(k - i) >=
           -kTouch * double(k - i);
  };
  for (int k = 0; k < n; ++k) {
    // Horizon of (s_k, h_k + e): the hull vertex of maximal backward-rising slope from it.
    const double qh = double(h[size_t(k)]) + error_allowed;
    auto slope = [&](int i) { return (double(h[size_t(i)]) - qh) / ((k - i) * step); };
    int t = -1;
    if (error_allowed == 0) {
      // The point itself: the vertices the monotone chain drops on pushing it lie on or under
      // its tangent, so the top left is the horizon (collinear ties dropped: the leftmost).
      while (hull.size() >= 2 && below_new_edge(k)) hull.pop_back();
      if (!hull.empty()) t = hull.back();
    } else if (!hull.empty()) {
      // A point above the profile: slopes to an upper hull from a point right of it are
      // unimodal along the hull; the first maximum is the leftmost argmax.
      int lo = 0, hi = int(hull.size()) - 1;
      while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (slope(hull[size_t(mid)]) >= slope(hull[size_t(mid) + 1]))
          hi = mid;
        else
          lo = mid + 1;
      }
      t = hull[size_t(lo)];
      while (hull.size() >= 2 && below_new_edge(k)) hull.pop_back();
    }
    // A horizon above the point (beyond float noise in the bilinear lerp): a rising slope.
    if (t >= 0 && double(h[size_t(t)]) - qh > kTouch)
      by_horizon[size_t(t)] = std::min(by_horizon[size_t(t)], k);
    hull.push_back(k);
  }
  // A start at sample j first violates at the earliest sample whose horizon lies strictly
  // after j: a suffix minimum over horizons, computed in place.
  int next = n;
  for (int j = n - 1; j >= 0; --j) {
    const int here = by_horizon[size_t(j)];
    first[size_t(j)] = next;
    next = std::min(next, here);
  }
}

namespace {

// Section 3.5 with blocked rays ignored: one horizon sweep per line (see safety_radius.h).
SafetyRadii compute_unblocked(const ReliefMap& map, const SafetyRadiusOptions& o, int cap) {
  const int W = map.width, H = map.height;
  const PaddedHeights rows(map, cap + 4, false), columns(map, cap + 4, true);
  const double two_pi = 2 * glm::pi<double>();
  const double step = o.step;
  const int per_centerline = std::max(1, int(std::lround(1.0 / step)));
  // Per direction, its own radius array (directions run in parallel); min-reduced at the end.
  std::vector<std::vector<uint8_t>> per_direction(size_t(o.directions));
  parallel_for(
      size_t(o.directions),
      [&](size_t d_begin, size_t d_end) {
        std::vector<float> h;
        std::vector<int> hull, first;
        for (size_t d = d_begin; d < d_end; ++d) {
          std::vector<uint8_t>& radius = per_direction[d];
          radius.assign(size_t(W) * H, uint8_t(cap));
          const double theta = two_pi * (double(d) + 0.5) / o.directions;
          const double cx = std::cos(theta), cy = std::sin(theta);
          // Line coordinates: a along the ray's major axis (forward), b across; the grid is
          // the map or its transpose so that a runs along memory rows. A line is b = c + ub a.
          const bool major_x = std::abs(cx) >= std::abs(cy);
          const PaddedHeights& grid = major_x ? rows : columns;
          const int A = grid.width(), B = grid.height();
          const bool flip = major_x ? cx < 0 : cy < 0;
          const double ub = major_x ? cy / std::abs(cx) : cx / std::abs(cy);
          const double c_min = -0.5 - std::max(-0.5 * ub, (A - 0.5) * ub);
          const double c_max = B - 0.5 - std::min(-0.5 * ub, (A - 0.5) * ub);
          const double spacing = 1.0 / o.starts;
          for (double c = c_min + 0.5 * spacing; c < c_max; c += spacing) {
            // The part of the line inside the map.
            double a0 = -0.5, a1 = A - 0.5;
            if (ub != 0) {
              const double at_lo = (-0.5 - c) / ub, at_hi = (B - 0.5 - c) / ub;
              a0 = std::max(a0, std::min(at_lo, at_hi));
              a1 = std::min(a1, std::max(at_lo, at_hi));
            } else if (c < -0.5 || c >= B - 0.5) {
              continue;
            }
            if (a0 > a1) continue;
            // Samples from the entry to cap + 1 centerlines past the exit (wrapping there).
            const long k0 = long(std::ceil(a0 / step));
            const long k1 = long(std::floor((a1 + cap + 1) / step));
            h.resize(size_t(k1 - k0 + 1));
            for (long k = k0; k <= k1; ++k) {
              const double a = k * step;
              h[size_t(k - k0)] = grid(flip ? (A - 1) - a : a, c + ub * a);
            }
            first_unblocked_violations(h, step, o.error_allowed, hull, first);
            // Starts: centerline crossings (integer a) inside the map.
            const long j_lo = std::max<long>(long(std::ceil(std::max(a0, 0.0))), 0);
            const long j_hi = std::min<long>(long(std::floor(a1)), A - 1);
            const int n = int(h.size());
            for (long ja = j_lo; ja <= j_hi; ++ja) {
              const long j = ja * per_centerline - k0;
              const int tb = std::clamp(int(std::floor(c + ub * double(ja) + 0.5)), 0, B - 1);
              int r = cap;
              if (first[size_t(j)] < n)
                r = std::min(cap, int(std::ceil((first[size_t(j)] - j) * step - 1e-9)) - 1);
              const int ta = flip ? (A - 1) - int(ja) : int(ja);
              const size_t idx = major_x ? size_t(tb) * W + ta : size_t(ta) * W + tb;
              radius[idx] = std::min(radius[idx], uint8_t(std::max(r, 0)));
            }
          }
        }
      },
      1);
  SafetyRadii out;
  out.width = W;
  out.height = H;
  out.radius.assign(size_t(W) * H, o.max_over_directions ? uint8_t(0) : uint8_t(cap));
  for (const auto& r : per_direction)
    for (size_t i = 0; i < r.size(); ++i)
      out.radius[i] =
          o.max_over_directions ? std::max(out.radius[i], r[i]) : std::min(out.radius[i], r[i]);
  return out;
}

// Blocked rays counted: every texel, direction and start scans the profile ahead.
SafetyRadii compute_conservative(const ReliefMap& map, const SafetyRadiusOptions& o, int cap) {
  const DepthSampler depth(map);
  SafetyRadii out;
  out.width = map.width;
  out.height = map.height;
  out.radius.assign(size_t(map.width) * map.height, 0);
  const double two_pi = 2 * glm::pi<double>();
  parallel_for(
      out.radius.size(),
      [&](size_t begin, size_t end) {
        for (size_t idx = begin; idx < end; ++idx) {
          const int i = int(idx % map.width), j = int(idx / map.width);
          int combined = o.max_over_directions ? 0 : cap;  // over the directions
          for (int d = 0; d < o.directions && (o.max_over_directions || combined > 0); ++d) {
            int radius = o.max_over_directions ? cap : combined;  // this direction's
            const double theta = two_pi * (d + 0.5) / o.directions;
            const double cx = std::cos(theta), cy = std::sin(theta);
            const bool major_x = std::abs(cx) >= std::abs(cy);
            // Per unit of the major axis (one centerline), the ray moves (ux, uy) texels.
            const double ux = major_x ? (cx > 0 ? 1 : -1) : cx / std::abs(cy);
            const double uy = major_x ? cy / std::abs(cx) : (cy > 0 ? 1 : -1);
            for (int st = 0; st < o.starts && radius > 0; ++st) {
              // Start on the texel's centerline across the major axis, anywhere within the texel.
              const double off = o.starts > 1 ? -0.5 + double(st) / (o.starts - 1) : 0.0;
              const double x0 = i + (major_x ? 0.0 : off), y0 = j + (major_x ? off : 0.0);
              // Texel-centre coordinates -> texture coordinates; height = -depth.
              auto height = [&](int k) {
                const double a = k * o.step;
                return -depth(x0 + ux * a, y0 + uy * a);
              };
              // Only violations before radius + 1 centerlines can lower the radius further.
              const int limit = int(std::ceil((radius + 1) / o.step)) + 1;
              const double s = scan_profile(height, limit, o.step, o.error_allowed);
              if (std::isfinite(s)) radius = std::min(radius, int(std::ceil(s)) - 1);
            }
            combined = o.max_over_directions ? std::max(combined, radius) : radius;
          }
          out.radius[idx] = uint8_t(std::clamp(combined, 0, 255));
        }
      },
      64);
  return out;
}

}  // namespace

int effective_max_radius(const ReliefMap& map, const SafetyRadiusOptions& o) {
  if (o.max_radius > 0) return std::min(o.max_radius, 255);
  return std::clamp(std::max(map.width, map.height), 1, 255);
}

SafetyRadii compute_safety_radii(const ReliefMap& map, const SafetyRadiusOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const int cap = effective_max_radius(map, o);
  SafetyRadii out =
      o.ignore_blocked ? compute_unblocked(map, o, cap) : compute_conservative(map, o, cap);
  out.compute_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

SafetyRadii cached_safety_radii(const ReliefMap& map, const SafetyRadiusOptions& o) {
  constexpr int kAlgorithmVersion = 3;  // bump when compute_safety_radii changes its answers
  char options[256];
  std::snprintf(options, sizeof options, "v%d|%d|%d|%.9g|%d|%.9g|%d|%d|", kAlgorithmVersion,
                o.directions, o.starts, o.step, effective_max_radius(map, o), o.error_allowed,
                int(o.ignore_blocked), int(o.max_over_directions));
  return cached_precompute("safety_radius", options, map.width, map.height, map.content_hash(),
                           &SafetyRadii::radius, [&] { return compute_safety_radii(map, o); });
}

}  // namespace rl
