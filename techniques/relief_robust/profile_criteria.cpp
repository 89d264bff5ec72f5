#include "profile_criteria.h"

#include <algorithm>
#include <limits>

namespace rl {

namespace {

// The conservative criterion's scan from the start h(0) over heights produced by height(k):
// the first k < limit at which a descending ray above the start could have entered and left
// the surface, or limit.
template <typename Height>
int scan_profile(Height&& height, int limit, double step, double error_allowed) {
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
      if (max_slope > slope + 1e-12) return k;
    } else if (max_h > hk + 1e-12) {
      return k;
    }
    max_slope = std::max(max_slope, (hk - error_allowed - h0) / s);
    max_h = std::max(max_h, hk - error_allowed);
  }
  return limit;
}

}  // namespace

double first_two_hit_distance(const std::vector<double>& h, double step, double error_allowed) {
  const int n = int(h.size());
  const int k = scan_profile([&](int i) { return h[size_t(i)]; }, n, step, error_allowed);
  return k < n ? k * step : std::numeric_limits<double>::infinity();
}

int first_two_hit_after(const std::vector<double>& h, int j, int limit, double step,
                        double error_allowed) {
  return first_two_hit_after(h.data(), int(h.size()), j, limit, step, error_allowed);
}

int first_two_hit_after(const double* h, int n, int j, int limit, double step,
                        double error_allowed) {
  const int reach = std::min(limit, n - j);
  const int k = scan_profile([&](int i) { return h[size_t(j + i)]; }, reach, step, error_allowed);
  return k < reach ? j + k : n;
}

// Height (depth units) within which a ray counts as touching, not entering, the surface: ten
// times the rounding of float heights in [-1, 0], a 4000th of an 8-bit depth step.
constexpr double kTouch = 1e-6;

void UnblockedLineSweep::begin(double step, double error_allowed) {
  step_ = step;
  error_allowed_ = error_allowed;
  hull_.clear();
  by_horizon_.clear();
  top_ = read_ = 0;
  latest_horizon_ = -1;
}

bool UnblockedLineSweep::read(const float* const h, const int n, int last_start) {
  // by_horizon[t]: the first sample whose horizon is sample t (none yet: the int maximum).
  by_horizon_.resize(size_t(n), std::numeric_limits<int>::max());
  int* const by_horizon = by_horizon_.data();
  hull_.resize(size_t(n) + 1);
  int* const hull = hull_.data();
  int top = top_;  // the hull is hull[0..top)
  // Is the hull's top on, under, or within kTouch above the edge (second, k)? Such a vertex is
  // a collinear tie: a ray along the edge touches it without dipping in. The tolerance keeps
  // float rounding on planar slopes (a pyramid's face, sampled by bilinear lerps) from
  // turning exact ties into dips of 1e-8 that zeroed the radii of whole faces.
  auto below_new_edge = [&](int k) {
    const int i = hull[top - 2], j = hull[top - 1];
    return double(j - i) * (double(h[k]) - h[i]) - (double(h[j]) - h[i]) * double(k - i) >=
           -kTouch * double(k - i);
  };
  int k = read_;
  for (; k < n && latest_horizon_ <= last_start; ++k) {
    // Horizon of (s_k, h_k + e): the hull vertex of maximal backward-rising slope from it.
    const double qh = double(h[k]) + error_allowed_;
    auto slope = [&](int i) { return (double(h[i]) - qh) / ((k - i) * step_); };
    int t = -1;
    if (error_allowed_ == 0) {
      // The point itself: the vertices the monotone chain drops on pushing it lie on or under
      // its tangent, so the top left is the horizon (collinear ties dropped: the leftmost).
      while (top >= 2 && below_new_edge(k)) --top;
      if (top > 0) t = hull[top - 1];
    } else if (top > 0) {
      // A point above the profile: slopes to an upper hull from a point right of it are
      // unimodal along the hull; the first maximum is the leftmost argmax.
      int lo = 0, hi = top - 1;
      while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (slope(hull[mid]) >= slope(hull[mid + 1]))
          hi = mid;
        else
          lo = mid + 1;
      }
      t = hull[lo];
      while (top >= 2 && below_new_edge(k)) --top;
    }
    // A horizon above the point (beyond float noise in the bilinear lerp): a rising slope.
    if (t >= 0 && double(h[t]) - qh > kTouch) {
      by_horizon[t] = std::min(by_horizon[t], k);
      latest_horizon_ = std::max(latest_horizon_, t);
    }
    hull[top++] = k;
  }
  top_ = top;
  read_ = k;
  return latest_horizon_ > last_start;
}

void UnblockedLineSweep::answers(std::vector<int>& first) const {
  // A start at sample j first violates at the earliest sample whose horizon lies strictly
  // after j: a suffix minimum over horizons.
  const int n = read_;
  first.resize(size_t(n));
  int next = n;
  for (int j = n - 1; j >= 0; --j) {
    first[size_t(j)] = next;
    next = std::min(next, by_horizon_[size_t(j)]);
  }
}

void first_unblocked_violations(const std::vector<float>& heights, double step,
                                double error_allowed, std::vector<int>& first) {
  UnblockedLineSweep sweep;
  sweep.begin(step, error_allowed);
  sweep.read(heights, int(heights.size()));
  sweep.answers(first);
}

// The conservative criterion (every ray above the start counts) for every start at once; the
// per-start scan it must equal is scan_profile. For a start j, let m be the first later sample
// higher than h[j]. Before m every sample is at most h[j], and the scan's test is whether an
// earlier sample lies above the chord from j, i.e. whether the sample is hidden from j: the
// first hidden sample V(j). From m on, every later sample at most h[j] is hidden behind m,
// and a higher one violates when it lies below the highest sample since m: the first sample
// after m lower than the maximum since m, D(m), which depends on m alone.
void first_conservative_violations(const std::vector<double>& heights, double step, int first_start,
                                   int stride, std::vector<int>& scratch,
                                   std::vector<int>& first_out) {
  first_conservative_violations(heights.data(), int(heights.size()), step, first_start, stride,
                                scratch, first_out);
}

namespace {
constexpr double kTie = 1e-12;  // scan_profile's slope tolerance: double-rounding collinear
}  // namespace

void first_conservative_violations(const double* const h, const int n, double step, int first_start,
                                   int stride, std::vector<int>& scratch,
                                   std::vector<int>& first_out) {
  first_out.assign(size_t(n), n);
  if (n == 0) return;
  scratch.resize(2 * size_t(n));
  int* const first = first_out.data();
  int* const descent = scratch.data();
  int* const stack = scratch.data() + n;
  int top = 0;
  // V(j), kept in first[j]: the first k >= j + 2 at which k - 1 lies above the chord from j
  // to k. The samples up to k - 1 are all seen from j, so the slopes from j rise along them
  // and a start's test at k compares with the slope to k - 1 alone. Among the starts still
  // waiting, the slope to k - 1 does not fall from an earlier start to a later one (a later
  // start sees the rest of the same rising view), so the starts that fail at k are the top of
  // a stack.
  // Only the starts wait on the stack (the other samples' answers are left unfinished).
  for (int k = first_start + 2, next_start = first_start; k < n; ++k) {
    if (k - 2 == next_start) {
      stack[top++] = next_start;
      next_start += stride;
    }
    const double before = h[k - 1], here = h[k];
    while (top > 0) {
      // slope(j, k - 1) > slope(j, k) + kTie, multiplied out (no division in the hot loop).
      const int j = stack[top - 1];
      const double near = k - 1 - j, far = k - j;
      if (!((before - h[j]) * far > (here - h[j]) * near + kTie * step * near * far)) break;
      first[j] = k;
      --top;
    }
  }
  // From the right, in one pass: D(m), the first k > m below max(h[m..k-1]) by more than the
  // tie; and m(j), the next higher sample, with a stack of rising heights. A start's first
  // violation is V(j) if it comes before m(j), else D(m(j)).
  descent[n - 1] = n;
  top = 0;
  for (int j = n - 1; j >= 0; --j) {
    if (j < n - 1) {
      const double hj = h[j], next = h[j + 1];
      if (hj <= next) {
        descent[j] = descent[j + 1];  // h[j] never sets the maximum
      } else if (hj > next + kTie) {
        descent[j] = j + 1;
      } else {
        // A fall within the tie (planar slopes in double rounding): h[j] sets the maximum
        // only until a sample lies below it by more than the tie.
        int k = j + 2;
        while (k < descent[j + 1] && !(hj > h[k] + kTie)) ++k;
        descent[j] = k;
      }
    }
    while (top > 0 && h[stack[top - 1]] <= h[j]) --top;
    const int m = top > 0 ? stack[top - 1] : n;
    if (first[j] >= m) first[j] = m < n ? descent[m] : n;
    stack[top++] = j;
  }
}

int first_conservative_violation_before(const double* const h, const int j, const int end,
                                        double step) {
  const double hj = h[j];
  int k = j + 1;
  // Before m, the first sample higher than h[j]: V(j), tested as the line sweep's stack tests it.
  for (; k < end && h[k] <= hj; ++k) {
    if (k < j + 2) continue;
    const double before = h[k - 1], here = h[k];
    const double near = k - 1 - j, far = k - j;
    if ((before - hj) * far > (here - hj) * near + kTie * step * near * far) return k;
  }
  if (k >= end) return end;
  // From m on: D(m), the first sample below the highest since m by more than the tie.
  double highest = h[k];
  for (++k; k < end; ++k) {
    if (highest > h[k] + kTie) return k;
    highest = std::max(highest, h[k]);
  }
  return end;
}

}  // namespace rl
