#pragma once
// The lines along which the safety radii are computed (Baboud & Decoret 2006, Section 3.5), and
// the sweep of every sampled direction over them: for each direction, lines 1/starts texel
// apart, each sampled every `step` along the ray's major axis, whose starts (the samples on
// centerlines) narrow the radii of the texels they cross. The criterion that answers a line's
// starts is the caller's (safety_radius.cpp); what is here is shared by both variants.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/gtc/constants.hpp>

#include "core/fast_floor.h"
#include "core/parallel.h"
#include "core/uninitialized.h"
#include "profile_criteria.h"
#include "safety_radius.h"

namespace rl::radius_lines {

// Heights (= -depth) of the map padded by `pad` texels of wrapped copies on every side, so the
// line sweep samples bilinearly without a modulo per sample; its transpose swaps x and y, so
// that a sweep always runs along rows (contiguous memory) whatever its major axis.
class PaddedHeights {
 public:
  PaddedHeights(const ReliefMap& m, int pad);

  // The same heights with x and y swapped, copied in tiles (gathering the map's columns
  // straight from its texels read a cache line per height: 22 ms at 1024^2 against 2 for rows).
  PaddedHeights transposed() const;

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

// Whether a ray at azimuth theta runs mostly along x: its lines are then swept along the map's
// rows, else along its transpose's.
inline bool x_is_major(double theta) {
  return std::abs(std::cos(theta)) >= std::abs(std::sin(theta));
}

// One line of a direction, in line coordinates: a along the ray's major axis (forward), b across,
// on a grid (the map, or its transpose where y is the major axis) whose rows run along a. The
// line is b = c + ub a; its samples are k = 0, 1, ... at a = (k0 + k) step, from where it
// enters the map to at most cap + 1 centerlines past its exit (wrapping there). Its starts are
// the samples on centerlines (whole a) inside the map: begin, begin + stride, ..., end. Each
// narrows (by the minimum) the radius of the texels within `reach` across of its crossing (0:
// the texel it lies in), in `radius`, laid out like the grid so that a line's writes run along
// memory rows too.
struct SweptLine {
  const PaddedHeights* grid;
  int A, B;   // the grid's width (along a) and height
  bool flip;  // the ray runs towards smaller a: the grid is read mirrored
  double c, ub, step, reach;
  long k0, length;
  long begin, end, stride;  // the starts
  long ja_begin;            // the centerline of the first start
  uint8_t* radius;

  template <typename T>
  T sample(long k) const {
    const double a = double(k0 + k) * step;
    return grid->sample<T>(flip ? (A - 1) - a : a, c + ub * a);
  }
  long starts() const { return (end - begin) / stride + 1; }
  long start(long i) const { return begin + i * stride; }
  // f(texel) for each texel the i-th start narrows.
  template <typename F>
  void each_texel(long i, F&& f) const {
    const long ja = ja_begin + i;
    const double b = c + ub * double(ja);
    const int ta = flip ? (A - 1) - int(ja) : int(ja);
    const int tb_lo = std::max(0, int(floor_fast(b - reach + 0.5)));
    const int tb_hi = std::min(B - 1, int(floor_fast(b + reach + 0.5)));
    for (int tb = tb_lo; tb <= tb_hi; ++tb) f(radius[size_t(tb) * A + size_t(ta)]);
  }
  // The largest radius among the texels the i-th start narrows.
  uint8_t largest(long i) const {
    uint8_t most = 0;
    each_texel(i, [&](uint8_t at) { most = std::max(most, at); });
    return most;
  }
  // Narrows them to at most r; returns the largest radius left among them.
  uint8_t narrow(long i, uint8_t r) const {
    uint8_t most = 0;
    each_texel(i, [&](uint8_t& at) {
      at = std::min(at, r);
      most = std::max(most, at);
    });
    return most;
  }
};

// The radius a start at sample j allows when its first violation is sample `first`: the whole
// centerlines before it, less one.
inline int radius_before(long first, long j, double step, int cap) {
  return std::max(0, std::min(cap, int(ceil_fast(double(first - j) * step - 1e-9)) - 1));
}

// A line's profile, sampled only as far as its criterion reads it: a prefix (read_to), or
// ranges in chunks of kChunk samples (read_range), not both on one line.
template <typename T>
class LineProfile {
  // Samples from .. to - 1 into h. The line is taken by value, so that the compiler keeps it in
  // registers rather than reloading it after every store into h (a double store may alias it).
  static void sample(const SweptLine line, long from, long to, T* h) {
    for (long k = from; k < to; ++k) h[k] = line.sample<T>(k);
  }

 public:
  static constexpr long kChunk = 64;
  LineProfile(const SweptLine& line, UninitializedVector<T>& h, std::vector<uint8_t>& chunk_read)
      : line_(line), h_(h), chunk_read_(chunk_read) {
    h_.resize(size_t(line.length));
    chunk_read_.assign(size_t((line.length + kChunk - 1) / kChunk), 0);
  }
  long length() const { return line_.length; }
  const T* data() const { return h_.data(); }
  // The samples read from 0 on (by read_to).
  long prefix() const { return prefix_; }
  bool whole() const { return prefix_ >= line_.length; }
  // At least the first `count` samples, or all of them.
  void read_to(long count) {
    const long to = std::min(count, line_.length);
    if (prefix_ < to) sample(line_, prefix_, to, h_.data());
    prefix_ = std::max(prefix_, to);
  }
  // At least samples from .. to - 1 (to <= length()).
  void read_range(long from, long to) {
    for (long chunk = from / kChunk; chunk * kChunk < to; ++chunk) {
      if (chunk_read_[size_t(chunk)]) continue;
      chunk_read_[size_t(chunk)] = 1;
      sample(line_, chunk * kChunk, std::min(line_.length, (chunk + 1) * kChunk), h_.data());
    }
  }

 private:
  const SweptLine& line_;
  UninitializedVector<T>& h_;
  std::vector<uint8_t>& chunk_read_;
  long prefix_ = 0;
};

// What one core reuses from line to line and direction to direction, on cache lines of its own
// (the cores' scratch sits side by side, and a field one core writes on a line another core
// reads made some runs of the same radii 50% slower than others).
template <typename T>
struct alignas(64) LineScratch {
  UninitializedVector<T> h;
  std::vector<uint8_t> chunk_read;
  std::vector<int> scratch, first, tail_first;
  UnblockedLineSweep unblocked;
  bool read_whole_last = false;  // whether the line before needed its whole profile
  // The samples the line before would have had its starts read one at a time (the conservative
  // criterion's NearStarts), -1 where it is the first of its direction.
  long near_work_last = -1;
  long starts_answered_alone = 0;  // by NearStarts, over every line this core swept
};

// Narrows the texels of every start of `line` by its answer: first[j] for the start at sample
// j, an index into the profile, none among the `read` samples where it equals `read`. With
// `span` (samples per radius), returns the sum over the starts of the span of the largest radius
// they leave in their texels, or the long maximum once that passes `work_limit` (summed no
// further); else 0.
long narrow_by_answers(SweptLine line, const int* first, long read, int cap,
                       const long* span = nullptr, long work_limit = 0);

// One direction of Section 3.5's sampling: lines 1/starts texel apart, each handed with its
// profile to `answer_line(line, profile, scratch)`, which narrows the texels of its starts.
template <typename T, typename AnswerLine>
void sweep_direction(const PaddedHeights& rows, const PaddedHeights& columns,
                     const SafetyRadiusOptions& o, int cap, double reach, double theta,
                     AnswerLine& answer_line, LineScratch<T>& scratch,
                     std::vector<uint8_t>& radius) {
  const double step = o.step;
  const int per_centerline = std::max(1, int(std::lround(1.0 / step)));
  const double cx = std::cos(theta), cy = std::sin(theta);
  const bool major_x = x_is_major(theta);
  const PaddedHeights& grid = major_x ? rows : columns;
  const int A = grid.width(), B = grid.height();
  const double ub = major_x ? cy / std::abs(cx) : cx / std::abs(cy);
  const double c_min = -0.5 - std::max(-0.5 * ub, (A - 0.5) * ub);
  const double c_max = B - 0.5 - std::min(-0.5 * ub, (A - 0.5) * ub);
  const double spacing = 1.0 / o.starts;
  scratch.near_work_last = -1;
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
    const long k1 = long(std::floor((a1 + cap + 1) / step));
    const SweptLine line{&grid,
                         A,
                         B,
                         major_x ? cx < 0 : cy < 0,
                         c,
                         ub,
                         step,
                         reach,
                         k0,
                         k1 - k0 + 1,
                         ja_lo * per_centerline - k0,
                         ja_hi * per_centerline - k0,
                         per_centerline,
                         ja_lo,
                         radius.data()};
    LineProfile<T> profile(line, scratch.h, scratch.chunk_read);
    answer_line(line, profile, scratch);
  }
}

// The radii over every direction, in parallel, each direction's in the layout of its grid
// (GridRadii). Kept as the minimum over directions, each core narrows one array per layout
// of its own (a fresh 1 MB array per direction at 1024^2 was page faults and fills for
// nothing); as Section 3.5's words have it (the maximum over directions), each direction needs
// its own array. Combined after, transposing where a layout is the map's transpose.
struct GridRadii {
  bool transposed = false;
  std::vector<uint8_t> radius;
};

// f(x, y) for every texel of a W x H map, in 32 x 32 tiles, on every core: an array in the
// transposed layout is then read a cache line per tile row rather than one per texel.
template <typename F>
void each_texel_tiled(int W, int H, F&& f) {
  constexpr int kTile = 32;
  parallel_for(
      size_t((H + kTile - 1) / kTile),
      [&](size_t begin, size_t end) {
        for (int y0 = int(begin) * kTile; y0 < std::min(H, int(end) * kTile); y0 += kTile)
          for (int x0 = 0; x0 < W; x0 += kTile)
            for (int y = y0; y < std::min(H, y0 + kTile); ++y)
              for (int x = x0; x < std::min(W, x0 + kTile); ++x) f(x, y);
      },
      1);
}

// The radius of texel (x, y) in g's layout.
size_t index_in(const GridRadii& g, int x, int y, int W, int H);

// The narrowest (or, with `widest`, the widest) radius of each texel over the arrays in
// `radii`, in the map's layout.
std::vector<uint8_t> combined(const std::vector<GridRadii>& radii, int W, int H, bool widest,
                              uint8_t cap);

// A share_while_zeros for sweep_lines under which no round is shared.
constexpr double kNoSharedRounds = 2;

// Every array of `radii` (one per core and layout) set to the narrowest radii among them;
// returns the share of texels at 0.
double share_narrowest(std::vector<GridRadii>& radii, int W, int H, uint8_t cap);

// The radii over every sampled direction: each direction's lines are handed to `answer_line`
// (sweep_direction), each texel narrowed by the starts `reach` across from it. With the minimum
// over directions kept and `share_while_zeros` at most 1, the first directions go in rounds of
// one per core, after each of which every core goes on from the narrowest radii found so far,
// in both layouts, while at least that share of the texels is at 0 (a criterion that answers
// only what can still lower a radius then has less to answer), and the rest are dealt out.
template <typename T, typename AnswerLine>
SafetyRadii sweep_lines(const ReliefMap& map, const SafetyRadiusOptions& o, int cap, double reach,
                        double share_while_zeros, AnswerLine&& answer_line) {
  // On the rock wall at 1024^2, 3 shared rounds took the starts answered alone from 19.7 M (1)
  // and 14.8 M (2) to 12.7 M, all 8 to 11.0 M; each round waits for its slowest direction.
  constexpr size_t kMaxSharedRounds = 3;
  const int W = map.width, H = map.height;
  const PaddedHeights rows(map, cap + 4), columns = rows.transposed();
  const size_t workers = parallel_workers();
  std::vector<GridRadii> radii(o.max_over_directions ? size_t(o.directions) : 2 * workers);
  std::vector<LineScratch<T>> scratch(workers);
  auto sweep = [&](size_t d, size_t lane) {
    const double theta = 2 * glm::pi<double>() * (double(d) + 0.5) / o.directions;
    const bool transposed = !x_is_major(theta);
    GridRadii& g = radii[o.max_over_directions ? d : 2 * lane + size_t(transposed)];
    if (g.radius.empty()) g.radius.assign(size_t(W) * H, uint8_t(cap));
    g.transposed = transposed;
    sweep_direction<T>(rows, columns, o, cap, reach, theta, answer_line, scratch[lane], g.radius);
  };
  std::vector<size_t> order;
  // Directions order[from .. to), each to the core free first.
  auto sweep_round = [&](size_t from, size_t to) {
    parallel_for_workers(
        to - from,
        [&](size_t worker, size_t begin, size_t end) {
          for (size_t i = from + begin; i < from + end; ++i) sweep(order[i], worker);
        },
        1);
  };
  // Directions order[from .. to) dealt out in turn (lane c: from + c, from + c + lanes, ...),
  // each lane narrowing arrays of its own: which directions meet in an array, and so what a
  // criterion that reads the radii has to answer, does not depend on which core is faster.
  auto deal_round = [&](size_t from, size_t to) {
    parallel_for_workers(
        workers,
        [&](size_t, size_t lane_begin, size_t lane_end) {
          for (size_t lane = lane_begin; lane < lane_end; ++lane)
            for (size_t i = from + lane; i < to; i += workers) sweep(order[i], lane);
        },
        1);
  };
  // Directions a quarter turn apart first (0, 4, 8, 12, 1, 5, ... of 16), so that each round
  // of one direction per core looks across different features.
  const size_t D = size_t(o.directions), quarter = std::max<size_t>(1, D / 4);
  for (size_t first = 0; first < quarter; ++first)
    for (size_t d = first; d < D; d += quarter) order.push_back(d);
  const bool shares = !o.max_over_directions && share_while_zeros <= 1;
  size_t done = 0;
  for (bool sharing = shares; sharing && done + workers < D;) {
    deal_round(done, done + workers);
    done += workers;
    sharing = share_narrowest(radii, W, H, uint8_t(cap)) >= share_while_zeros &&
              done < kMaxSharedRounds * workers;
  }
  if (shares)
    deal_round(done, order.size());
  else
    sweep_round(done, order.size());
  SafetyRadii out;
  out.width = W;
  out.height = H;
  out.radius = combined(radii, W, H, o.max_over_directions, uint8_t(cap));
  for (const LineScratch<T>& s : scratch) out.starts_answered_alone += s.starts_answered_alone;
  return out;
}

}  // namespace rl::radius_lines
