#include "relief/ao_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/elapsed.h"
#include "core/parallel.h"
#include "core/precompute_cache.h"

namespace rl {
namespace {

// Heights in texel units (top = height_texels), laid out like the map's texels, and bilinear
// samples of them at texel coordinates (texel centre i at i), wrapping like GL_REPEAT.
struct HeightGrid {
  const ReliefMap& map;  // its layout and wrapping (ReliefMap::index)
  std::vector<float> h;
  float at(int x, int y) const { return h[map.index(x, y)]; }
  double sample(double x, double y) const {
    const double fx = std::floor(x), fy = std::floor(y);
    const int x0 = int(fx), y0 = int(fy);
    const double a = x - fx, b = y - fy;
    const double top = at(x0, y0) * (1 - a) + at(x0 + 1, y0) * a;
    const double bottom = at(x0, y0 + 1) * (1 - a) + at(x0 + 1, y0 + 1) * a;
    return top * (1 - b) + bottom * b;
  }
};

// Squared cosine of the horizon's elevation along (dx, dy) from texel (x, y): r^2 of the
// polygon vertex on the unit hemisphere, 1 where nothing rises above the horizontal.
double horizon_cos2(const HeightGrid& g, int x, int y, double dx, double dy, double highest,
                    int max_steps) {
  const double h0 = g.at(x, y);
  double best = 0;  // tan of the horizon elevation; below the horizontal does not count
  for (int k = 1; k <= max_steps; ++k) {
    // Nothing from here on can rise above the horizon found so far.
    if ((highest - h0) <= best * k) break;
    const double rise = g.sample(x + dx * k, y + dy * k) - h0;
    best = std::max(best, rise / k);
  }
  return 1.0 / (1.0 + best * best);
}

}  // namespace

AoMap compute_ao_map(const ReliefMap& map, const AoMapOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  HeightGrid g{map, {}};
  g.h.resize(map.relief.size());
  for (size_t i = 0; i < g.h.size(); ++i)
    g.h[i] = float((1.0 - double(map.relief[i].a)) * o.height_texels);
  const double highest = *std::max_element(g.h.begin(), g.h.end());
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
  out.visibility.assign(g.h.size(), 1.0f);
  parallel_for(
      g.h.size(),
      [&](size_t begin, size_t end) {
        std::vector<double> r(n);
        for (size_t i = begin; i < end; ++i) {
          const int x = int(i % map.width), y = int(i / map.width);
          for (int j = 0; j < n; ++j)
            r[j] = std::sqrt(horizon_cos2(g, x, y, cx[j], sy[j], highest, max_steps));
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

void filter_occluded_texels(const ReliefMap& map, std::vector<float>& visibility) {
  const std::vector<float> raw = visibility;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      const size_t i = size_t(y) * map.width + x;
      if (raw[i] >= 1.0f) continue;
      double sum = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) sum += raw[map.index(x + dx, y + dy)];
      visibility[i] = float(sum / 9.0);
    }
}

AoMap cached_ao_map(const ReliefMap& map, const AoMapOptions& o, AoMapMethod method) {
  // Bump when a method changes its answers (2: the fragment shader's open directions are made
  // exactly 1, as the CPU's always were).
  constexpr int kAlgorithmVersion = 2;
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
