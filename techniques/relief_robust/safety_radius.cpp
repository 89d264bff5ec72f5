#include "safety_radius.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include <glm/gtc/constants.hpp>

#include "core/fast_floor.h"
#include "core/parallel.h"
#include "core/precompute_cache.h"
#include "core/uninitialized.h"
#include "core/wrap.h"

namespace rl {

int SafetyRadii::zero_count() const {
  return int(std::count(radius.begin(), radius.end(), uint8_t(0)));
}

namespace {

// Heights (= -depth) of the map padded by `pad` texels of wrapped copies on every side, so the
// line sweep samples bilinearly without a modulo per sample; its transpose swaps x and y, so
// that a sweep always runs along rows (contiguous memory) whatever its major axis.
class PaddedHeights {
 public:
  PaddedHeights(const ReliefMap& m, int pad)
      : w_(m.width), h_(m.height), pad_(pad), stride_(size_t(w_ + 2 * pad)) {
    data_.resize(stride_ * size_t(h_ + 2 * pad));  // first touched by the fill, on every core
    std::vector<int> source_x(stride_);
    for (size_t i = 0; i < stride_; ++i) source_x[i] = wrap_index(long(i) - pad, w_);
    parallel_for(
        size_t(h_ + 2 * pad),
        [&](size_t begin, size_t end) {
          for (size_t row = begin; row < end; ++row) {
            const int sy = wrap_index(long(row) - pad, h_);
            float* out = &data_[row * stride_];
            for (size_t i = 0; i < stride_; ++i)
              out[i] = -m.relief[size_t(sy) * m.width + size_t(source_x[i])].a;
          }
        },
        16);
  }

  // The same heights with x and y swapped, copied in tiles (gathering the map's columns
  // straight from its texels read a cache line per height: 22 ms at 1024^2 against 2 for rows).
  PaddedHeights transposed() const {
    PaddedHeights t;
    t.w_ = h_;
    t.h_ = w_;
    t.pad_ = pad_;
    t.stride_ = size_t(t.w_ + 2 * pad_);
    const size_t rows = size_t(h_ + 2 * pad_), columns = stride_;  // of this grid
    t.data_.resize(data_.size());
    constexpr size_t kTile = 32;
    parallel_for((columns + kTile - 1) / kTile,
                 [&](size_t begin, size_t end) {
                   for (size_t x0 = begin * kTile; x0 < std::min(columns, end * kTile); x0 += kTile)
                     for (size_t y0 = 0; y0 < rows; y0 += kTile)
                       for (size_t x = x0; x < std::min(columns, x0 + kTile); ++x)
                         for (size_t y = y0; y < std::min(rows, y0 + kTile); ++y)
                           t.data_[x * t.stride_ + y] = data_[y * stride_ + x];
                 },
                 1);
    return t;
  }

  int width() const { return w_; }
  int height() const { return h_; }
  // Bilinear height at texel-centre coordinates (x, y), both above -pad, in the arithmetic of
  // T: float for Section 3.5's sweep (its touch tolerance absorbs float rounding), double for
  // the conservative one, whose slope tolerance of 1e-12 needs a planar face sampled along a
  // line to stay collinear to double rounding.
  template <typename T>
  T sample(double x, double y) const {
    const double px = x + pad_, py = y + pad_;
    const long ix = long(px), iy = long(py);  // floor: both are positive
    const T fx = T(px - double(ix)), fy = T(py - double(iy));
    const float* r0 = &data_[size_t(iy) * stride_ + size_t(ix)];
    const float* r1 = r0 + stride_;
    const T top = T(r0[0]) + (T(r0[1]) - T(r0[0])) * fx;
    const T bottom = T(r1[0]) + (T(r1[1]) - T(r1[0])) * fx;
    return top + (bottom - top) * fy;
  }

 private:
  PaddedHeights() = default;
  int w_ = 0, h_ = 0, pad_ = 0;
  size_t stride_ = 0;
  UninitializedVector<float> data_;
};

// The starts of one line that the criterion must answer: samples j_begin, j_begin + stride,
// ..., up to j_end (inclusive), each a centerline crossing inside the map.
struct LineStarts {
  long begin, end, stride;
};

// Whether a ray at azimuth theta runs mostly along x: its lines are then swept along the map's
// rows, else along its transpose's.
bool x_is_major(double theta) {
  return std::abs(std::cos(theta)) >= std::abs(std::sin(theta));
}

// What one core reuses from line to line and direction to direction.
template <typename T>
struct LineScratch {
  std::vector<T> h;
  std::vector<int> scratch, first, tail_first;
  UnblockedLineSweep unblocked;
  bool read_whole_last = false;  // whether the line before needed its whole profile
};

// A line's profile, sampled only as far as its criterion reads it: h holds its first h.size()
// samples of `length`.
template <typename T, typename Sampler>
class LineProfile {
 public:
  LineProfile(std::vector<T>& h, size_t length, Sampler sample_to)
      : h(h), length(length), sample_to_(std::move(sample_to)) {}
  std::vector<T>& h;
  const size_t length;
  bool whole() const { return h.size() >= length; }
  // At least `count` samples, or all of them.
  void read_to(size_t count) { sample_to_(std::min(count, length)); }

 private:
  Sampler sample_to_;
};

// One direction of Section 3.5's sampling: lines 1/starts texel apart, each sampled every `step`
// from where it enters the map to at most cap + 1 centerlines past its exit (wrapping there);
// `first_violations(profile, starts, line)` reads the profile as far as it needs, leaves each
// start's first violation in line.first (an index into the profile) and returns the count of
// samples those answers cover (an answer equal to it: none among them), and each start bounds (by
// the minimum, into `radius`) the radius of the texel its centerline crossing lies in, or of every
// texel within `reach` across. `radius` is laid out like the grid the lines run along (the map, or
// its transpose where y is the major axis), so that a line's writes run along memory rows too.
template <typename T, typename FirstViolations>
void sweep_direction(const PaddedHeights& rows, const PaddedHeights& columns,
                     const SafetyRadiusOptions& o, int cap, double reach, double theta,
                     FirstViolations& first_violations, LineScratch<T>& line,
                     std::vector<uint8_t>& radius) {
  const double step = o.step;
  const int per_centerline = std::max(1, int(std::lround(1.0 / step)));
  const double cx = std::cos(theta), cy = std::sin(theta);
  // Line coordinates: a along the ray's major axis (forward), b across; the grid is the map or
  // its transpose so that a runs along memory rows. A line is b = c + ub a.
  const bool major_x = x_is_major(theta);
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
    // Starts: centerline crossings (integer a) inside the map.
    const long ja_lo = std::max<long>(long(std::ceil(std::max(a0, 0.0))), 0);
    const long ja_hi = std::min<long>(long(std::floor(a1)), A - 1);
    if (ja_lo > ja_hi) continue;
    const long k0 = long(std::ceil(a0 / step));
    const LineStarts starts{ja_lo * per_centerline - k0, ja_hi * per_centerline - k0,
                            per_centerline};
    std::vector<T>& h = line.h;
    h.clear();
    const long k1 = long(std::floor((a1 + cap + 1) / step));
    LineProfile profile(h, size_t(k1 - k0 + 1), [&](size_t count) {
      for (long k = k0 + long(h.size()); k < k0 + long(count); ++k) {
        const double a = k * step;
        h.push_back(grid.sample<T>(flip ? (A - 1) - a : a, c + ub * a));
      }
    });
    const int n = first_violations(profile, starts, line);
    const int* const first = line.first.data();
    for (long ja = ja_lo; ja <= ja_hi; ++ja) {
      const long j = ja * per_centerline - k0;
      const double b = c + ub * double(ja);
      int r = cap;
      if (first[j] < n) r = std::min(cap, int(ceil_fast((first[j] - j) * step - 1e-9)) - 1);
      const uint8_t here = uint8_t(std::max(r, 0));
      const int ta = flip ? (A - 1) - int(ja) : int(ja);
      // Every texel within `reach` of the crossing (0: the texel it lies in).
      const int tb_lo = std::max(0, int(floor_fast(b - reach + 0.5)));
      const int tb_hi = std::min(B - 1, int(floor_fast(b + reach + 0.5)));
      for (int tb = tb_lo; tb <= tb_hi; ++tb) {
        uint8_t& at = radius[size_t(tb) * A + size_t(ta)];
        at = std::min(at, here);
      }
    }
  }
}

// Section 3.5's radii over every direction, in parallel, each direction's in the layout of its
// grid (GridRadii). Kept as the minimum over directions, each core narrows one array per layout
// of its own (a fresh 1 MB array per direction at 1024^2 was page faults and fills for
// nothing); as Section 3.5's words have it (the maximum over directions), each direction needs
// its own array. Combined after, transposing where a layout is the map's transpose.
struct GridRadii {
  bool transposed = false;
  std::vector<uint8_t> radius;
};

template <typename T, typename FirstViolations>
SafetyRadii sweep_lines(const ReliefMap& map, const SafetyRadiusOptions& o, int cap, double reach,
                        FirstViolations&& first_violations) {
  const int W = map.width, H = map.height;
  const PaddedHeights rows(map, cap + 4), columns = rows.transposed();
  const size_t workers = parallel_workers();
  std::vector<GridRadii> radii(o.max_over_directions ? size_t(o.directions) : 2 * workers);
  std::vector<LineScratch<T>> scratch(workers);
  parallel_for_workers(
      size_t(o.directions),
      [&](size_t worker, size_t d_begin, size_t d_end) {
        for (size_t d = d_begin; d < d_end; ++d) {
          const double theta = 2 * glm::pi<double>() * (double(d) + 0.5) / o.directions;
          const bool transposed = !x_is_major(theta);
          GridRadii& g = radii[o.max_over_directions ? d : 2 * worker + size_t(transposed)];
          if (g.radius.empty()) g.radius.assign(size_t(W) * H, uint8_t(cap));
          g.transposed = transposed;
          sweep_direction<T>(rows, columns, o, cap, reach, theta, first_violations, scratch[worker],
                             g.radius);
        }
      },
      1);
  SafetyRadii out;
  out.width = W;
  out.height = H;
  out.radius.assign(size_t(W) * H, o.max_over_directions ? uint8_t(0) : uint8_t(cap));
  for (const GridRadii& g : radii) {
    if (g.radius.empty()) continue;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        uint8_t& into = out.radius[size_t(y) * W + x];
        const uint8_t r = g.radius[g.transposed ? size_t(x) * H + y : size_t(y) * W + x];
        into = o.max_over_directions ? std::max(into, r) : std::min(into, r);
      }
  }
  return out;
}

// Section 3.5 with blocked rays ignored: one horizon sweep per line (see safety_radius.h),
// read past the map's edge only until every start has its first violation. That reach of cap + 1
// centerlines was 28% of the samples read at 1024^2; on the rock wall 1.7% of the lines need all
// of it (58% more than 8 centerlines), on the bricks, whose flat tops have large radii, 77%.
SafetyRadii compute_unblocked(const ReliefMap& map, const SafetyRadiusOptions& o, int cap) {
  return sweep_lines<float>(map, o, cap, 0.0,
                            [&](auto& profile, LineStarts starts, LineScratch<float>& line) {
                              UnblockedLineSweep& sweep = line.unblocked;
                              sweep.begin(o.step, o.error_allowed);
                              size_t chunk = 8 * size_t(starts.stride);  // 8 centerlines
                              for (size_t count = size_t(starts.end) + 2;; count += chunk) {
                                profile.read_to(count);
                                if (sweep.read(profile.h, int(starts.end)) || profile.whole())
                                  break;
                                chunk *= 2;
                              }
                              sweep.answers(line.first);
                              return sweep.samples_read();
                            });
}

// Blocked rays counted: with no error allowed, every start of a line at once in O(samples);
// with an allowance, each start scans ahead up to the cap. A texel takes the radii of every
// line within a line spacing of it, so the two sampled lines that bracket any ray crossing
// it both bound its radius (on the one-texel walls of the robust tests, the crossing's own
// lines alone missed 19 of 2,048 grazing rays, the bracketing lines 8).
//
// A start's answer depends on the samples from it on alone. So the profile is read 64
// centerlines past the map's edge first, and only where some start has no violation there is
// the rest read and the line answered again from that start on. (On the rock wall at 1024^2,
// 64 was faster than 8, 24 and 128: a line answered twice costs more than the samples saved.)
SafetyRadii compute_conservative(const ReliefMap& map, const SafetyRadiusOptions& o, int cap) {
  const int limit = int(std::ceil((cap + 1) / o.step)) + 1;
  // Line answers for the starts from `from` (a start) on, over all of h.
  auto answer_from = [&](const std::vector<double>& h, LineStarts starts, long from,
                         LineScratch<double>& line) {
    const int n = int(h.size());
    line.first.resize(h.size());
    if (o.error_allowed == 0) {
      std::vector<int>& tail = line.tail_first;
      first_conservative_violations(h.data() + from, n - int(from), o.step, 0, int(starts.stride),
                                    line.scratch, tail);
      for (long j = from; j <= starts.end; j += starts.stride)
        line.first[size_t(j)] = tail[size_t(j - from)] + int(from);
    } else {
      for (long j = from; j <= starts.end; j += starts.stride)
        line.first[size_t(j)] = first_two_hit_after(h, int(j), limit, o.step, o.error_allowed);
    }
  };
  return sweep_lines<double>(
      map, o, cap, 1.0 / o.starts,
      [&](auto& profile, LineStarts starts, LineScratch<double>& line) {
        // A line whose neighbour needed the rest likely does too (a brick's flat top): it is
        // read whole at once rather than answered twice.
        if (line.read_whole_last) profile.read_to(profile.length);
        profile.read_to(size_t(starts.end) + 1 + 64 * size_t(starts.stride));  // 64 centerlines
        answer_from(profile.h, starts, starts.begin, line);
        long from = starts.begin;
        while (from <= starts.end && line.first[size_t(from)] < int(profile.h.size()))
          from += starts.stride;
        line.read_whole_last = from <= starts.end;
        if (from <= starts.end && !profile.whole()) {
          profile.read_to(profile.length);
          answer_from(profile.h, starts, from, line);
        }
        return int(profile.h.size());
      });
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
  constexpr int kAlgorithmVersion = 4;  // bump when compute_safety_radii changes its answers
  char options[256];
  std::snprintf(options, sizeof options, "v%d|%d|%d|%.9g|%d|%.9g|%d|%d|", kAlgorithmVersion,
                o.directions, o.starts, o.step, effective_max_radius(map, o), o.error_allowed,
                int(o.ignore_blocked), int(o.max_over_directions));
  return cached_precompute("safety_radius", options, map.width, map.height, map.content_hash(),
                           &SafetyRadii::radius, [&] { return compute_safety_radii(map, o); });
}

}  // namespace rl
