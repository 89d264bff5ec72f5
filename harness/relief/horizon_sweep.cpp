#include "relief/horizon_sweep.h"

#include <algorithm>
#include <cmath>
#include <glm/vec2.hpp>

#include "core/fast_floor.h"
#include "core/parallel.h"

namespace rl {
namespace {

// x taken into [0, n) (x within a few n of it, as every coordinate here is).
double wrapped(double x, int n) {
  while (x < 0) x += n;
  while (x >= n) x -= n;
  return x;
}

int floor_of(float x) {
  return int(floor_fast(x));
}
int ceil_of(float x) {
  return int(ceil_fast(x));
}

// The lines of one azimuth in the frame (s along it, t across it): line j lies at t = t0 + j,
// its samples at s = s0 + k for whole k. Texel (x, y) sits at s = x c + y sn, t = y c - x sn.
struct LineFrame {
  float c, sn;
  int t0, s0, lines;
  float s_of(float x, float y) const { return x * c + y * sn; }
  float t_of(float x, float y) const { return y * c - x * sn; }
  float x_at(float s, float t) const { return s * c - t * sn; }
  float y_at(float s, float t) const { return s * sn + t * c; }
};

// The least and greatest s of the texel centres' rectangle [0, w-1] x [0, h-1] inside the strip
// ta <= t <= tb: reached at a corner inside the strip or where a strip edge crosses a side.
void strip_extent(const LineFrame& f, float w1, float h1, float ta, float tb, float& lo,
                  float& hi) {
  lo = 1e30f;
  hi = -1e30f;
  const float cx[4] = {0, w1, w1, 0}, cy[4] = {0, 0, h1, h1};
  for (int i = 0; i < 4; ++i) {
    const float ax = cx[i], ay = cy[i], bx = cx[(i + 1) % 4], by = cy[(i + 1) % 4];
    const float at = f.t_of(ax, ay), bt = f.t_of(bx, by);
    if (at >= ta && at <= tb) {
      lo = std::min(lo, f.s_of(ax, ay));
      hi = std::max(hi, f.s_of(ax, ay));
    }
    for (float edge : {ta, tb}) {
      if ((at - edge) * (bt - edge) > 0 || at == bt) continue;
      const float u = (edge - at) / (bt - at);
      const float s = f.s_of(ax + u * (bx - ax), ay + u * (by - ay));
      lo = std::min(lo, s);
      hi = std::max(hi, s);
    }
  }
}

// The texel centres 0 .. n - 1 within the span of four coordinates (with a margin for rounding:
// the partition itself is decided by slot_of).
glm::ivec2 centres_within(const float v[4], int n) {
  const float lo = std::min(std::min(v[0], v[1]), std::min(v[2], v[3]));
  const float hi = std::max(std::max(v[0], v[1]), std::max(v[2], v[3]));
  return {std::max(0, ceil_of(lo - 1e-3f)), std::min(n - 1, floor_of(hi + 1e-3f))};
}

// One line of a bundle: its samples (from the bundle's first k on) and the upper hull of those
// read so far, nearest last.
struct SweptLine {
  std::vector<float> height;
  std::vector<int32_t> hull;
};

// The sample of `line` at or after the hull's nearest where the slope from the point (s, h) is
// steepest: seen from a point before the hull, the slope along it rises, then falls.
int tangent_from(const SweptLine& line, const LineFrame& f, int k_first, float s, float h) {
  const std::vector<int32_t>& hull = line.hull;
  size_t i = hull.size() - 1;
  float best = (line.height[size_t(hull[i] - k_first)] - h) / (float(f.s0 + hull[i]) - s);
  while (i > 0) {
    const int next = hull[i - 1];
    const float slope = (line.height[size_t(next - k_first)] - h) / (float(f.s0 + next) - s);
    if (slope <= best) break;
    best = slope;
    --i;
  }
  return hull[i];
}

// Reads sample k of `line` (at t) and takes it into the hull: the nearest hull point leaves
// when it lies on or under the chord from the new point to the one after it.
void take_sample(const TiledHeights& g, double x, double y, int k, int k_first, SweptLine& line) {
  const float hk = g.bilinear_wrapped(x, y);
  std::vector<int32_t>& hull = line.hull;
  const float* height = line.height.data() - k_first;
  while (hull.size() >= 2) {
    const int a = hull[hull.size() - 1], b = hull[hull.size() - 2];
    if ((height[a] - hk) * float(b - k) > (height[b] - hk) * float(a - k)) break;
    hull.pop_back();
  }
  line.height[size_t(k - k_first)] = hk;
  hull.push_back(k);
}

// Which strip (between lines j and j + 1) and which first far sample k a texel centre has; the
// one partition every texel is assigned by.
struct TexelSlot {
  float s, u;
  int j, k;
};
TexelSlot slot_of(const LineFrame& f, int near_steps, int x, int y) {
  TexelSlot t;
  t.s = f.s_of(float(x), float(y));
  t.u = f.t_of(float(x), float(y)) - float(f.t0);
  t.j = floor_of(t.u);
  t.k = ceil_of(t.s + float(near_steps)) - f.s0;
  return t;
}

// The horizon of texel (x, y), between lines `below` and `above` whose hulls hold the samples
// from the texel's first far one on.
float texel_horizon(const TiledHeights& g, const LineFrame& f, const HorizonSweepOptions& o,
                    const TexelSlot& p, int x, int y, const SweptLine& below,
                    const SweptLine& above, int k_first) {
  const float hp = g.at(x, y);
  float best = 0;  // below the horizontal counts as open
  for (int m = 1; m <= o.near_steps; ++m)
    best = std::max(best, (g.bilinear(x + double(f.c) * m, y + double(f.sn) * m) - hp) / float(m));
  // Beyond, the texel's ray runs between the lines, `across` of the way from one to the other.
  // Two estimates of its steepest point, each biased on its own where the other is not (tests:
  // AoMap.SweepStaysCloseToThePerTexelMarch): the point between the two lines' own tangent
  // points, which follows a ridge crossing both lines obliquely; and the steepest point of
  // the lines' blend by distance between those two, which does not overstate a peak that only
  // one line crosses (a blend of the two slopes would).
  const float across = p.u - float(p.j);
  const int ka = tangent_from(below, f, k_first, p.s, hp);
  const int kb = tangent_from(above, f, k_first, p.s, hp);
  const float k_between = (1 - across) * float(ka) + across * float(kb);
  const float h_between = (1 - across) * below.height[size_t(ka - k_first)] +
                          across * above.height[size_t(kb - k_first)];
  best = std::max(best, (h_between - hp) / (float(f.s0) + k_between - p.s));
  const int lo = std::min(ka, kb), hi = std::min(std::max(ka, kb), lo + 16);
  for (int kt = lo; kt <= hi; ++kt) {
    const float blend = (1 - across) * below.height[size_t(kt - k_first)] +
                        across * above.height[size_t(kt - k_first)];
    best = std::max(best, (blend - hp) / (float(f.s0 + kt) - p.s));
  }
  return best;
}

// Lines first_line .. first_line + strips swept together from their far ends, each texel of the
// strips between them resolved when the sweep reaches its first far sample.
void sweep_bundle(const TiledHeights& g, const LineFrame& f, const HorizonSweepOptions& o,
                  int first_line, int strips, std::vector<SweptLine>& lines,
                  std::vector<float>& tan_out) {
  const float w1 = float(g.width() - 1), h1 = float(g.height() - 1);
  float lo, hi;
  strip_extent(f, w1, h1, float(f.t0 + first_line), float(f.t0 + first_line + strips), lo, hi);
  if (lo > hi) return;  // the strips miss the map
  const int k_first = floor_of(lo + float(o.near_steps)) - f.s0 - 1;
  const int k_texels = ceil_of(hi + float(o.near_steps)) - f.s0 + 1;
  const int k_last = k_texels + o.reach;
  // Each strip's own stretch of k holding texels.
  std::vector<glm::ivec2> strip_k(static_cast<size_t>(strips));
  for (int i = 0; i < strips; ++i) {
    float a, b;
    strip_extent(f, w1, h1, float(f.t0 + first_line + i), float(f.t0 + first_line + i + 1), a, b);
    strip_k[size_t(i)] = a > b ? glm::ivec2(1, 0)
                               : glm::ivec2(floor_of(a + float(o.near_steps)) - f.s0 - 1,
                                            ceil_of(b + float(o.near_steps)) - f.s0 + 1);
  }
  lines.resize(size_t(strips) + 1);
  std::vector<glm::dvec2> at(lines.size());  // each line's sample point, wrapped
  for (size_t i = 0; i < lines.size(); ++i) {
    lines[i].height.resize(size_t(k_last - k_first + 1));
    lines[i].hull.clear();
    const double s = f.s0 + k_last, t = f.t0 + first_line + int(i);
    at[i] = {wrapped(s * f.c - t * f.sn, g.width()), wrapped(s * f.sn + t * f.c, g.height())};
  }
  for (int k = k_last; k >= k_first; --k) {
    for (size_t i = 0; i < lines.size(); ++i) {
      glm::dvec2& q = at[i];
      take_sample(g, q.x, q.y, k, k_first, lines[i]);
      g.step_back_wrapped(q.x, q.y, f.c, f.sn);  // one sample back
    }
    if (k > k_texels) continue;
    // The texels whose first far sample is k: in the rotated unit square s in (S - 1, S],
    // t in [t, t + 1) of each strip, at most 2 x 2 texel centres in its bounding box.
    const float S = float(f.s0 + k - o.near_steps);
    for (int i = 0; i < strips; ++i) {
      if (k < strip_k[size_t(i)].x || k > strip_k[size_t(i)].y) continue;
      const float t = float(f.t0 + first_line + i);
      const float xs[4] = {f.x_at(S - 1, t), f.x_at(S, t), f.x_at(S - 1, t + 1), f.x_at(S, t + 1)};
      const float ys[4] = {f.y_at(S - 1, t), f.y_at(S, t), f.y_at(S - 1, t + 1), f.y_at(S, t + 1)};
      const glm::ivec2 xr = centres_within(xs, g.width()), yr = centres_within(ys, g.height());
      for (int y = yr.x; y <= yr.y; ++y)
        for (int x = xr.x; x <= xr.y; ++x) {
          const TexelSlot p = slot_of(f, o.near_steps, x, y);
          if (p.j != first_line + i || p.k != k) continue;
          tan_out[size_t(y) * g.width() + size_t(x)] =
              texel_horizon(g, f, o, p, x, y, lines[size_t(i)], lines[size_t(i) + 1], k_first);
        }
    }
  }
}

}  // namespace

TiledHeights::TiledHeights(int width, int height, std::vector<float> heights)
    : w_(width), h_(height), padded_(size_t(width + 1) * (height + 1)) {
  for (int y = 0; y <= h_; ++y)
    for (int x = 0; x <= w_; ++x)
      padded_[size_t(y) * (w_ + 1) + size_t(x)] = heights[size_t(y % h_) * w_ + size_t(x % w_)];
}

void TiledHeights::step_back_wrapped(double& x, double& y, double dx, double dy) const {
  x -= dx;
  y -= dy;
  // x + w can round to w itself when x is a hair below 0: each test after the one before.
  if (x < 0) x += w_;
  if (x >= w_) x -= w_;
  if (y < 0) y += h_;
  if (y >= h_) y -= h_;
}

float TiledHeights::bilinear(double x, double y) const {
  return bilinear_wrapped(wrapped(x, w_), wrapped(y, h_));
}

void sweep_horizon(const TiledHeights& g, double phi, const HorizonSweepOptions& o,
                   std::vector<float>& tan_out) {
  LineFrame f;
  f.c = float(std::cos(phi));
  f.sn = float(std::sin(phi));
  const float w1 = float(g.width() - 1), h1 = float(g.height() - 1);
  const float ts[4] = {f.t_of(0, 0), f.t_of(w1, 0), f.t_of(w1, h1), f.t_of(0, h1)};
  const float ss[4] = {f.s_of(0, 0), f.s_of(w1, 0), f.s_of(w1, h1), f.s_of(0, h1)};
  f.t0 = int(std::floor(*std::min_element(ts, ts + 4))) - 1;
  f.s0 = int(std::floor(*std::min_element(ss, ss + 4))) - 1;
  f.lines = int(std::ceil(*std::max_element(ts, ts + 4))) - f.t0 + 2;
  tan_out.assign(size_t(g.width()) * g.height(), 0.0f);
  constexpr int kStrips = 8;  // strips per bundle: a bundle's lines share the cache lines read
  const int bundles = (f.lines - 1 + kStrips - 1) / kStrips;
  parallel_for(
      size_t(bundles),
      [&](size_t begin, size_t end) {
        std::vector<SweptLine> lines;
        for (size_t b = begin; b < end; ++b) {
          const int first = int(b) * kStrips;
          sweep_bundle(g, f, o, first, std::min(kStrips, f.lines - 1 - first), lines, tan_out);
        }
      },
      1);
}

}  // namespace rl
