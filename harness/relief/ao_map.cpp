#include "relief/ao_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <glm/glm.hpp>

#include "core/elapsed.h"
#include "core/fast_floor.h"
#include "core/parallel.h"
#include "core/precompute_cache.h"
#include "core/uninitialized.h"
#include "core/wrap.h"
#include "relief/horizon_sweep.h"

namespace rl {
namespace {

// Heights in texel units (top = height_texels) with a pyramid of block maxima, for a horizon
// search that skips, whole, the stretches of a profile that cannot rise above the horizon found
// so far. Level 0 is the map repeated into a grid with room for a top-level block past the
// map's far edge (so a box that starts inside the map is read without wrapping again), rounded
// up to whole top-level blocks so that every level halves exactly; level l holds the maximum of
// each 2^l x 2^l block. (A power-of-two grid would do too, but costs 4x the map's memory at
// 4096^2; this one at most (1 + 1024 / side)^2.)
class HeightPyramid {
 public:
  static constexpr int kTop = 9;  // blocks of up to 512 texels: segments of up to 256 samples

  HeightPyramid(const ReliefMap& map, double height_texels) : w_(map.width), h_(map.height) {
    auto padded = [](int n) {
      const int block = 1 << kTop;
      return (n + block + block - 1) / block * block;  // >= n + one block, whole blocks
    };
    levels_.resize(kTop + 1);
    sizes_.resize(kTop + 1);
    sizes_[0] = {padded(w_), padded(h_)};
    std::vector<float>& base = levels_[0];
    base.resize(size_t(sizes_[0].x) * sizes_[0].y);
    for (int y = 0; y < sizes_[0].y; ++y)
      for (int x = 0; x < sizes_[0].x; ++x)
        base[size_t(y) * sizes_[0].x + x] =
            float((1.0 - double(map.relief[map.index(x, y)].a)) * height_texels);
    highest_ = *std::max_element(base.begin(), base.end());
    for (int l = 1; l <= kTop; ++l) {
      const glm::ivec2 below = sizes_[l - 1];
      sizes_[l] = below / 2;
      levels_[l].resize(size_t(sizes_[l].x) * sizes_[l].y);
      for (int y = 0; y < sizes_[l].y; ++y)
        for (int x = 0; x < sizes_[l].x; ++x) {
          const float* r0 = &levels_[l - 1][size_t(2 * y) * below.x + 2 * x];
          const float* r1 = r0 + below.x;
          levels_[l][size_t(y) * sizes_[l].x + x] = std::max({r0[0], r0[1], r1[0], r1[1]});
        }
    }
  }

  double highest() const { return highest_; }
  float at(int x, int y) const { return levels_[0][size_t(y) * sizes_[0].x + x]; }

  // Bilinear sample at texel coordinates (texel centre i at i), wrapping like GL_REPEAT; the
  // same arithmetic as sampling the map itself.
  double sample(double x, double y) const {
    const double fx = floor_fast(x), fy = floor_fast(y);
    const int x0 = wrap_index(long(fx), w_), y0 = wrap_index(long(fy), h_);
    const double a = x - fx, b = y - fy;
    const double top = at(x0, y0) * (1 - a) + at(x0 + 1, y0) * a;
    const double bottom = at(x0, y0 + 1) * (1 - a) + at(x0 + 1, y0 + 1) * a;
    return top * (1 - b) + bottom * b;
  }

  // The highest height any bilinear sample in the box [x0, x1] x [y0, y1] (texel coordinates,
  // x0 <= x1, y0 <= y1, each side spanning fewer than 2^level - 1 texels) can take: the
  // maximum over the level's blocks the box's texels fall in (at most 2 x 2 of them).
  float box_max(double x0, double x1, double y0, double y1, int level) const {
    const long fx = long(floor_fast(x0)), fy = long(floor_fast(y0));
    const int lx = wrap_index(fx, w_), ly = wrap_index(fy, h_);
    const int hx = lx + int(long(floor_fast(x1)) - fx) + 1;  // + 1: the bilinear neighbour
    const int hy = ly + int(long(floor_fast(y1)) - fy) + 1;
    const std::vector<float>& m = levels_[level];
    const int stride = sizes_[level].x;
    float best = m[size_t(ly >> level) * stride + (lx >> level)];
    best = std::max(best, m[size_t(ly >> level) * stride + (hx >> level)]);
    best = std::max(best, m[size_t(hy >> level) * stride + (lx >> level)]);
    return std::max(best, m[size_t(hy >> level) * stride + (hx >> level)]);
  }

 private:
  int w_, h_;
  std::vector<std::vector<float>> levels_;
  std::vector<glm::ivec2> sizes_;
  double highest_ = 0;
};

// Squared cosine of the horizon's elevation along (dx, dy) from texel (x, y): r^2 of the
// polygon vertex on the unit hemisphere, 1 where nothing rises above the horizontal.
//
// The profile is sampled at steps k = 1, 2, ...; a segment of 2^(l-1) steps is skipped whole when
// the highest point of the blocks under it, seen from its nearest step, is no steeper than the
// horizon so far: no sample in it could raise the horizon, so the answer is the one the plain
// march gives, bit for bit (tests/test_ambient_occlusion.cpp). A skip tries a longer segment
// next; a segment that cannot be skipped is halved, down to single samples.
double horizon_cos2(const HeightPyramid& g, int x, int y, double dx, double dy, int max_steps) {
  const double h0 = g.at(x, y);
  const double reach = g.highest() - h0;
  double best = 0;  // tan of the horizon elevation; below the horizontal does not count
  int level = 2;
  for (int k = 1; k <= max_steps;) {
    // Nothing from here on can rise above the horizon found so far.
    if (reach <= best * k) break;
    if (level >= 2) {
      const int last = std::min(k + (1 << (level - 1)) - 1, max_steps);
      const double ax = x + dx * k, bx = x + dx * last, ay = y + dy * k, by = y + dy * last;
      const double top =
          g.box_max(std::min(ax, bx), std::max(ax, bx), std::min(ay, by), std::max(ay, by), level);
      // The margin covers a bilinear sample's rounding above its texels' maximum.
      if (top - h0 + 1e-9 <= best * k) {
        k = last + 1;
        level = std::min(level + 1, HeightPyramid::kTop);
      } else {
        --level;
      }
      continue;
    }
    const double rise = g.sample(x + dx * k, y + dy * k) - h0;
    best = std::max(best, rise / k);
    ++k;
    level = 2;
  }
  return 1.0 / (1.0 + best * best);
}

}  // namespace

AoMap compute_ao_map_march(const ReliefMap& map, const AoMapOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const HeightPyramid g(map, o.height_texels);
  const int n = std::max(3, o.directions);
  const int max_steps = 2 * std::max(map.width, map.height);
  std::vector<double> cx(n), sy(n);
  for (int j = 0; j < n; ++j) {
    const double phi = 2.0 * M_PI * j / n;
    cx[j] = std::cos(phi);
    sy[j] = std::sin(phi);
  }
  AoMap out;
  out.width = map.width;
  out.height = map.height;
  out.visibility.assign(map.relief.size(), 1.0f);
  parallel_for(
      out.visibility.size(),
      [&](size_t begin, size_t end) {
        std::vector<double> r(n);
        for (size_t i = begin; i < end; ++i) {
          const int x = int(i % map.width), y = int(i / map.width);
          for (int j = 0; j < n; ++j)
            r[j] = std::sqrt(horizon_cos2(g, x, y, cx[j], sy[j], max_steps));
          // Polygon area sum_j 1/2 r_j r_j+1 sin(2 pi / n) over that of an open sky.
          double area = 0;
          for (int j = 0; j < n; ++j) area += r[j] * r[(j + 1) % n];
          out.visibility[i] = float(std::min(1.0, area / n));
        }
      },
      64);
  if (o.filter) filter_occluded_texels(map, out.visibility);
  out.compute_ms = ms_since(start);
  return out;
}

AoMap compute_ao_map(const ReliefMap& map, const AoMapOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  UninitializedVector<float> heights(map.relief.size());
  parallel_for(
      heights.size(),
      [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i)
          heights[i] = float((1.0 - double(map.relief[i].a)) * o.height_texels);
      },
      1 << 14);
  const TiledHeights g(map.width, map.height, heights.data());
  HorizonSweepOptions sweep;
  // Features past one side length do not move the map (tests/test_ambient_occlusion.cpp); the
  // march reads twice as far. Half a side was 10% faster and moved the benchmark maps by 1e-4
  // at most, but lets a wall past it take up to 1.3% of a direction's visibility on a relief 8%
  // of the side tall, where a side lets 0.3% (results/precompute-times/README.md).
  sweep.reach = std::max(map.width, map.height);
  const int n = std::max(3, o.directions);
  // Polygon area sum_j 1/2 r_j r_j+1 sin(2 pi / n), one azimuth at a time.
  std::vector<float> r_first, r_prev, r_now;
  UninitializedVector<double> area(map.relief.size());  // first written by the second azimuth
  HorizonSweep sweep_at(g, sweep);
  for (int j = 0; j < n; ++j) {
    sweep_at(2.0 * M_PI * j / n, r_now);
    parallel_for(
        area.size(),
        [&](size_t begin, size_t end) {
          for (size_t i = begin; i < end; ++i) {
            r_now[i] = float(1.0 / std::sqrt(1.0 + double(r_now[i]) * r_now[i]));
            if (j == 1) area[i] = double(r_prev[i]) * r_now[i];
            if (j > 1) area[i] += double(r_prev[i]) * r_now[i];
          }
        },
        1 << 14);
    if (j == 0) r_first = r_now;
    std::swap(r_prev, r_now);
  }
  AoMap out;
  out.width = map.width;
  out.height = map.height;
  parallel_for(
      area.size(),
      [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i)  // in place: the last azimuth's r is read first
          r_prev[i] = float(std::min(1.0, (area[i] + double(r_prev[i]) * r_first[i]) / n));
      },
      1 << 14);
  out.visibility = std::move(r_prev);
  if (o.filter) filter_occluded_texels(map, out.visibility);
  out.compute_ms = ms_since(start);
  return out;
}

void filter_occluded_texels(const ReliefMap& map, std::vector<float>& visibility) {
  const std::vector<float> raw = visibility;
  const int w = map.width, h = map.height;
  parallel_for(
      size_t(h),
      [&](size_t begin, size_t end) {
        for (int y = int(begin); y < int(end); ++y) {
          // The rows above and below, wrapping; within a row only the first and last texel wrap.
          const float* rows[3] = {&raw[size_t(wrap_index(y - 1, h)) * w], &raw[size_t(y) * w],
                                  &raw[size_t(wrap_index(y + 1, h)) * w]};
          for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            if (raw[i] >= 1.0f) continue;
            const int left = x > 0 ? x - 1 : w - 1, right = x + 1 < w ? x + 1 : 0;
            double sum = 0;
            for (const float* row : rows) {  // the order of the sum: the same bits as before
              sum += row[left];
              sum += row[x];
              sum += row[right];
            }
            visibility[i] = float(sum / 9.0);
          }
        }
      },
      16);
}

AoMap cached_ao_map(const ReliefMap& map, const AoMapOptions& o, AoMapMethod method) {
  // Bump when a method changes its answers (2: the fragment shader's open directions are made
  // exactly 1, as the CPU's always were; 3: the CPU's map is the line sweep's, not the march's;
  // 4: the sweep no longer reads past its padding at the far edge; 5: it no longer leaves out
  // a row lying exactly on a bundle's first line, finds tangents without dividing, and reads
  // some lines farther, its bundles being wider).
  constexpr int kAlgorithmVersion = 5;
  char options[128];
  std::snprintf(options, sizeof options, "v%d|%d|%d|%.9g|%s|", kAlgorithmVersion, o.directions,
                int(o.filter), o.height_texels, method.name);
  const auto start = std::chrono::steady_clock::now();
  AoMap m = cached_precompute("ao_map", options, map.width, map.height, map.content_hash(),
                              &AoMap::visibility, [&] { return method.compute(map, o); });
  if (m.from_cache) m.compute_ms = ms_since(start);
  return m;
}

double ao_rescaled(double ao, double s) {
  ao = std::clamp(ao, 0.0, 1.0);
  const double r2 = ao;                                    // Eq. 4: r = sqrt(ao)
  const double r_squared_prime = s * s * (1.0 - r2) + r2;  // Eq. 5: (s H)^2 + r^2, H^2 = 1 - r^2
  if (!(r_squared_prime > 0)) return 1.0;                  // s = 0 and ao = 0: a flat relief
  return std::clamp(ao / r_squared_prime, 0.0, 1.0);       // Eq. 6
}

}  // namespace rl
