#include "radius_lines.h"

#include <limits>

#include "core/wrap.h"

namespace rl::radius_lines {

PaddedHeights::PaddedHeights(const ReliefMap& m, int pad)
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

PaddedHeights PaddedHeights::transposed() const {
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

long narrow_by_answers(const SweptLine line, const int* const first, long read, int cap,
                       const long* span, long work_limit) {
  auto here = [&](long i) {
    const long j = line.start(i);
    return uint8_t(first[size_t(j)] < read ? radius_before(first[size_t(j)], j, line.step, cap)
                                           : cap);
  };
  // Summing the spans while they stay within the limit, then narrowing alone: on the bricks,
  // whose large radii pass any limit within a few starts, the whole sum cost 3-5% of the radii's
  // time.
  long work = 0, i = 0;
  for (const long n = line.starts(); span && i < n && work <= work_limit; ++i)
    work += span[line.narrow(i, here(i))];
  for (const long n = line.starts(); i < n; ++i) {
    const uint8_t r = here(i);
    line.each_texel(i, [&](uint8_t& at) { at = std::min(at, r); });
  }
  return work <= work_limit ? work : std::numeric_limits<long>::max();
}

size_t index_in(const GridRadii& g, int x, int y, int W, int H) {
  return g.transposed ? size_t(x) * H + size_t(y) : size_t(y) * W + size_t(x);
}

std::vector<uint8_t> combined(const std::vector<GridRadii>& radii, int W, int H, bool widest,
                              uint8_t cap) {
  std::vector<uint8_t> out(size_t(W) * H, widest ? uint8_t(0) : cap);
  for (const GridRadii& g : radii) {
    if (g.radius.empty()) continue;
    each_texel_tiled(W, H, [&](int x, int y) {
      uint8_t& into = out[size_t(y) * W + size_t(x)];
      const uint8_t r = g.radius[index_in(g, x, y, W, H)];
      into = widest ? std::max(into, r) : std::min(into, r);
    });
  }
  return out;
}

double share_narrowest(std::vector<GridRadii>& radii, int W, int H, uint8_t cap) {
  const std::vector<uint8_t> known = combined(radii, W, H, false, cap);
  for (size_t k = 0; k < radii.size(); ++k) {
    GridRadii& g = radii[k];
    g.transposed = k % 2 == 1;  // one array per core and layout (sweep_lines)
    g.radius.resize(known.size());
    each_texel_tiled(W, H, [&](int x, int y) {
      g.radius[index_in(g, x, y, W, H)] = known[size_t(y) * W + size_t(x)];
    });
  }
  return double(std::count(known.begin(), known.end(), uint8_t(0))) / double(known.size());
}

}  // namespace rl::radius_lines
