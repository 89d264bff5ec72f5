#include "cone_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

#include <glm/gtc/constants.hpp>

#include "core/fast_floor.h"
#include "core/parallel.h"
#include "core/precompute_cache.h"
#include "relief/min_depth_pyramid.h"

namespace rl {
namespace {

// Bilinear depth at texel-centre coordinates (X = u * width - 0.5), wrapping like GL_REPEAT:
// the scan's inner loop, in float with a mask for power-of-two sides.
struct DepthSampler {
  int w, h;
  bool pow2;
  std::vector<float> d;
  explicit DepthSampler(const ReliefMap& map)
      : w(map.width),
        h(map.height),
        pow2((w & (w - 1)) == 0 && (h & (h - 1)) == 0),
        d(size_t(w) * h) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) d[size_t(y) * w + x] = map.depth_texel(x, y);
  }
  int wrap_x(int x) const { return pow2 ? x & (w - 1) : ((x % w) + w) % w; }
  int wrap_y(int y) const { return pow2 ? y & (h - 1) : ((y % h) + h) % h; }
  float at(int x, int y) const { return d[size_t(wrap_y(y)) * w + wrap_x(x)]; }
  float operator()(float X, float Y) const {
    const float fx = floor_fast(X), fy = floor_fast(Y);
    const int x0 = wrap_x(int(fx)), x1 = wrap_x(int(fx) + 1);
    const size_t r0 = size_t(wrap_y(int(fy))) * w, r1 = size_t(wrap_y(int(fy) + 1)) * w;
    const float ax = X - fx, ay = Y - fy;
    const float top = d[r0 + x0] + (d[r0 + x1] - d[r0 + x0]) * ax;
    const float bottom = d[r1 + x0] + (d[r1 + x1] - d[r1 + x0]) * ax;
    return top + (bottom - top) * ay;
  }
};

// For each scan direction (in texel units), a min-depth quadtree over levels finest..coarsest
// of only the cells where the bilinear surface may descend along that direction, widened by one
// cell: a segment [n - 1, n] of the scan (one texel long) on which the depth rises has a point
// of positive slope along the direction within one cell of either end. Elsewhere: +infinity.
std::vector<std::vector<std::vector<float>>> descending_quadtrees(
    const ReliefMap& map, const MinDepthPyramid& pyramid, const std::vector<glm::vec2>& steps,
    int finest, int coarsest) {
  const int w = map.width, h = map.height;
  std::vector<std::vector<std::vector<float>>> out(steps.size());
  parallel_for(
      steps.size(),
      [&](size_t begin, size_t end) {
        std::vector<uint8_t> flag(size_t(w) * h), wide(size_t(w) * h);
        for (size_t k = begin; k < end; ++k) {
          const glm::vec2 st = steps[k];
          for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
              const float d00 = map.depth_texel(x, y), d10 = map.depth_texel(x + 1, y),
                          d01 = map.depth_texel(x, y + 1), d11 = map.depth_texel(x + 1, y + 1);
              // The patch's slopes d/dX in {d10 - d00, d11 - d01}, d/dY in {d01 - d00,
              // d11 - d10}: the slope along st is largest at one pair of them.
              const float gx =
                  st.x > 0 ? std::max(d10 - d00, d11 - d01) : std::min(d10 - d00, d11 - d01);
              const float gy =
                  st.y > 0 ? std::max(d01 - d00, d11 - d10) : std::min(d01 - d00, d11 - d10);
              flag[size_t(y) * w + x] = st.x * gx + st.y * gy > -1e-7f;
            }
          for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
              uint8_t any = 0;
              for (int dy = -1; dy <= 1 && !any; ++dy)
                for (int dx = -1; dx <= 1 && !any; ++dx)
                  any = flag[size_t((y + dy + h) % h) * w + size_t((x + dx + w) % w)];
              wide[size_t(y) * w + x] = any;
            }
          std::vector<std::vector<float>>& levels = out[k];
          levels.resize(size_t(coarsest - finest + 1));
          for (int l = finest; l <= coarsest; ++l) {
            const int lw = w >> l, lh = h >> l, span = 1 << l;
            std::vector<float>& nodes = levels[size_t(l - finest)];
            nodes.assign(size_t(lw) * lh, std::numeric_limits<float>::infinity());
            for (int y = 0; y < lh * span; ++y)
              for (int x = 0; x < lw * span; ++x)
                if (wide[size_t(y) * w + x]) {
                  float& m = nodes[size_t(y >> l) * lw + size_t(x >> l)];
                  m = std::min(m, pyramid.level[0][size_t(y) * w + x]);
                }
          }
        }
      },
      1);
  return out;
}

// The scan samples each direction at whole steps from the texel's centre, so off its axes it
// never lands on a texel centre: the diagonal neighbour lies at sqrt 2, between steps 1 and 2,
// and the bilinear samples there are lower than that texel. A conservative cone may hold no
// surface point, so every texel centre within kNearTexels is held out exactly as well (the
// brute-force test found the misses only at the diagonal neighbours).
void hold_out_near_texel_centres(const ReliefMap& map, int side, std::vector<float>& ratio) {
  constexpr int kNearTexels = 3;
  parallel_for(
      ratio.size(),
      [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
          const int x = int(i % map.width), y = int(i / map.width);
          const double apex = map.depth_texel(x, y);
          for (int dy = -kNearTexels; dy <= kNearTexels; ++dy)
            for (int dx = -kNearTexels; dx <= kNearTexels; ++dx) {
              const double rise = apex - map.depth_texel(x + dx, y + dy);
              if (rise <= 0) continue;  // not above the apex (the apex itself included)
              ratio[i] = std::min(ratio[i], float(std::hypot(dx, dy) / (rise * side)));
            }
        }
      },
      256);
}

}  // namespace

std::vector<float> ratios_safe_under_filtering(const ConeMap& cones) {
  const int w = cones.width, h = cones.height;
  std::vector<float> out(cones.ratio.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float least = cones.ratio[size_t(y) * w + x];
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          least =
              std::min(least, cones.ratio[size_t((y + dy + h) % h) * w + size_t((x + dx + w) % w)]);
      out[size_t(y) * w + x] = least;
    }
  return out;
}

ConeMap compute_cone_map(const ReliefMap& map, const ConeMapOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const DepthSampler depth(map);
  ConeMap out;
  out.width = map.width;
  out.height = map.height;
  out.ratio.assign(size_t(map.width) * map.height, float(o.max_ratio));
  // One step is one texel (texels are square in the world); ratios are stored per longer side.
  const int side = std::max(map.width, map.height);
  std::vector<glm::vec2> step_texels(size_t(o.directions));
  for (int k = 0; k < o.directions; ++k) {
    const double a = 2.0 * glm::pi<double>() * k / o.directions;
    step_texels[size_t(k)] = glm::vec2(float(std::cos(a)), float(std::sin(a)));
  }
  // Regions that cannot narrow the cone are stepped over: a node of a min-depth quadtree
  // whose highest point h_min gives n / (apex - h_min) >= the ratio found (in steps) for the
  // nearest sample n in it holds no constraint (relief/min_depth_pyramid.h). Relaxed cones only
  // count where the surface descends along the scan, so each direction has its own quadtree
  // over just those cells.
  const MinDepthPyramid pyramid = build_min_depth_pyramid(map, 0.0f);
  const int finest = std::min(2, pyramid.levels() - 1);
  const int coarsest = std::min(5, pyramid.levels() - 1);
  const std::vector<std::vector<std::vector<float>>> descending =
      o.relaxed ? descending_quadtrees(map, pyramid, step_texels, finest, coarsest)
                : std::vector<std::vector<std::vector<float>>>();
  auto node_min = [&](size_t k, int level, int cx, int cy) {
    const int w = map.width >> level, h = map.height >> level;
    int nx = cx >> level, ny = cy >> level;
    if (depth.pow2) {
      nx &= w - 1;
      ny &= h - 1;
    } else {
      nx = ((nx % w) + w) % w;
      ny = ((ny % h) + h) % h;
    }
    const std::vector<float>& nodes =
        o.relaxed ? descending[k][size_t(level - finest)] : pyramid.level[size_t(level)];
    return nodes[size_t(ny) * w + nx];
  };
  parallel_for(
      out.ratio.size(),
      [&](size_t begin, size_t end) {
        const size_t directions = step_texels.size();
        std::vector<float> last_h(directions);  // depth at a direction's last sample
        std::vector<int> resume(directions);    // next step a direction samples
        std::vector<char> skipped(directions);  // its last step was a skip
        for (size_t i = begin; i < end; ++i) {
          const int x = int(i % size_t(map.width)), y = int(i / size_t(map.width));
          const float apex = depth.at(x, y);
          if (apex <= 0.0f) continue;  // at the top: no ray above to step for
          // In steps: ratio = n / (side * (apex - h)); stop at n >= best * apex * side.
          const float scale = float(side);
          float best_steps = float(o.max_ratio) * scale;  // best ratio * side
          // All directions advance together, one step at a time, so the scan ends at the
          // distance of the nearest constraint over every direction (a ring search), not at
          // each direction's own.
          std::fill(resume.begin(), resume.end(), 1);
          std::fill(skipped.begin(), skipped.end(), 0);
          // Loop while the nearer end of the segment [n - 1, n] could still narrow the cone.
          // In blocks of kChunk steps: every direction scans the block, then the bound is
          // checked again (a ring search at a coarser grain, without a per-step pass over all
          // directions).
          constexpr int kChunk = 8;
          for (int n0 = 1; float(n0 - 1) < best_steps * apex; n0 += kChunk) {
            for (size_t k = 0; k < directions; ++k)
              for (int n = std::max(n0, resume[k]);
                   n < n0 + kChunk && float(n - 1) < best_steps * apex;
                   n = std::max(n + 1, resume[k])) {
                const glm::vec2 st = step_texels[k];
                const float X = float(x) + st.x * float(n), Y = float(y) + st.y * float(n);
                const float h = depth(X, Y);
                if (!o.relaxed) {
                  if (h < apex) best_steps = std::min(best_steps, float(n) / (apex - h));
                } else if (n >= 2) {
                  // The segment [n - 1, n], with h linear on it: the ray from the top point
                  // through (s, h(s)) leaves the surface there iff h / s rises, i.e. iff
                  // h_n / n > h_{n-1} / (n - 1), and then on the whole segment, so the cone must
                  // exclude all of it; x / (apex - h) is monotone on it, least at an end.
                  const float h_prev =
                      skipped[k] ? depth(X - st.x, Y - st.y) : last_h[k];  // resumed: re-read
                  if (h * float(n - 1) > h_prev * float(n)) {
                    if (h < apex) best_steps = std::min(best_steps, float(n) / (apex - h));
                    if (h_prev < apex)
                      best_steps = std::min(best_steps, float(n - 1) / (apex - h_prev));
                  }
                }
                last_h[k] = h;
                skipped[k] = 0;
                resume[k] = n + 1;
                // Step over the coarsest node from here on that cannot narrow the cone.
                const int cx = int(floor_fast(X)), cy = int(floor_fast(Y));
                int skip_level = -1;
                for (int l = finest; l <= coarsest; ++l) {
                  if (float(n) < best_steps * (apex - node_min(k, l, cx, cy))) break;
                  skip_level = l;
                }
                if (skip_level < 0) continue;
                const float lo_x = float((cx >> skip_level) << skip_level),
                            lo_y = float((cy >> skip_level) << skip_level);
                const float span = float(1 << skip_level);
                float t_exit = 1e30f;
                if (st.x > 0) t_exit = std::min(t_exit, (lo_x + span - X) / st.x);
                if (st.x < 0) t_exit = std::min(t_exit, (lo_x - X) / st.x);
                if (st.y > 0) t_exit = std::min(t_exit, (lo_y + span - Y) / st.y);
                if (st.y < 0) t_exit = std::min(t_exit, (lo_y - Y) / st.y);
                if (int(t_exit) >= 1) {
                  resume[k] = n + 1 + int(t_exit);
                  skipped[k] = 1;
                }
              }
          }
          out.ratio[i] = best_steps / scale;
        }
      },
      256);
  if (!o.relaxed) hold_out_near_texel_centres(map, side, out.ratio);
  out.compute_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

ConeMap cached_cone_map(const ReliefMap& map, const ConeMapOptions& o) {
  constexpr int kAlgorithmVersion = 3;  // bump when compute_cone_map changes its answers
  char options[128];
  std::snprintf(options, sizeof options, "v%d|%d|%d|%.9g|", kAlgorithmVersion, int(o.relaxed),
                o.directions, o.max_ratio);
  return cached_precompute("cone_map", options, map.width, map.height, map.content_hash(),
                           &ConeMap::ratio, [&] { return compute_cone_map(map, o); });
}

}  // namespace rl
