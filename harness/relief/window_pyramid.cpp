#include "relief/window_pyramid.h"

#include <algorithm>

namespace rl {
namespace {

int wrap(int i, int n) {
  return ((i % n) + n) % n;
}

// One axis of a window level: per line of `n_lines` values `n` long (stride `along` between
// values, `across` between lines), per block I of b values, the least value over
// [(I - 1) b - 1, (I + 2) b - 1] (way 0), [I b - 1, (I + 2) b - 1] (way +1) or
// [(I - 1) b - 1, (I + 1) b - 1] (way -1), wrapping. Written to out[line * (n / b) + I].
std::vector<float> window_mins(const std::vector<float>& in, int n, int n_lines, size_t along,
                               size_t across, int b, int way) {
  const int blocks = n / b;
  std::vector<float> out(size_t(n_lines) * blocks);
  std::vector<float> block_min(static_cast<size_t>(blocks));
  for (int line = 0; line < n_lines; ++line) {
    const float* v = in.data() + size_t(line) * across;
    for (int B = 0; B < blocks; ++B) {
      float m = v[size_t(B * b) * along];
      for (int i = 1; i < b; ++i) m = std::min(m, v[size_t(B * b + i) * along]);
      block_min[size_t(B)] = m;
    }
    for (int I = 0; I < blocks; ++I) {
      // The blocks the window spans, and the cell just before the first.
      const int first = way > 0 ? I : I - 1, last = way < 0 ? I : I + 1;
      float m = v[size_t(wrap(first * b - 1, n)) * along];
      for (int B = first; B <= last; ++B) m = std::min(m, block_min[size_t(wrap(B, blocks))]);
      out[size_t(line) * blocks + I] = m;
    }
  }
  return out;
}

}  // namespace

std::vector<float> window_level(const std::vector<float>& cells, int W, int H, int b, int way_x,
                                int way_y) {
  const std::vector<float> rows = window_mins(cells, W, H, 1, size_t(W), b, way_x);  // H x (W / b)
  const int columns = W / b;
  // Down each column of `rows`: the same window along y, then transposed back to rows.
  const std::vector<float> cols = window_mins(rows, H, columns, size_t(columns), 1, b, way_y);
  std::vector<float> out(size_t(columns) * (H / b));
  for (int I = 0; I < columns; ++I)
    for (int J = 0; J < H / b; ++J) out[size_t(J) * columns + I] = cols[size_t(I) * (H / b) + J];
  return out;
}

}  // namespace rl
