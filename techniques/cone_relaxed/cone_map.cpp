#include "cone_map.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numeric>

#include "core/parallel.h"
#include "core/precompute_cache.h"
#include "core/wrap.h"

namespace rl {
namespace {

// The map's depths by texel, wrapping like GL_REPEAT (with a mask for power-of-two sides): what
// the line samples blend.
struct DepthSampler {
  int w, h;
  bool pow2;
  std::vector<float> d;
  explicit DepthSampler(const ReliefMap& map)
      : w(map.width),
        h(map.height),
        pow2((w & (w - 1)) == 0 && (h & (h - 1)) == 0),
        d(map.depths()) {}
  int wrap_x(int x) const { return pow2 ? x & (w - 1) : wrap_index(x, w); }
  int wrap_y(int y) const { return pow2 ? y & (h - 1) : wrap_index(y, h); }
  float at(int x, int y) const { return d[size_t(wrap_y(y)) * w + wrap_x(x)]; }
};

}  // namespace

std::vector<ConeScanDirection> cone_scan_directions(int at_least) {
  for (int m = 1;; ++m) {
    std::vector<ConeScanDirection> dirs;
    for (int q = -m; q <= m; ++q)
      for (int p = -m; p <= m; ++p)
        if ((p || q) && std::gcd(std::abs(p), std::abs(q)) == 1)
          dirs.push_back({p, q, std::max(std::abs(p), std::abs(q))});
    if (int(dirs.size()) < at_least && m < 16) continue;
    // Axes and diagonals first: their lines are cheapest, and the cones they find bound the
    // scans of the directions after them.
    std::stable_sort(
        dirs.begin(), dirs.end(),
        [](const ConeScanDirection& a, const ConeScanDirection& b) { return a.sub < b.sub; });
    return dirs;
  }
}

namespace {

// The texels of every line along (p, q), each a cycle of the map's wrap (every texel lies on
// exactly one): line l is order[start[l] .. start[l + 1]).
struct Lines {
  std::vector<uint32_t> order;
  std::vector<size_t> start;
};

Lines lines_along(int w, int h, int p, int q) {
  Lines out;
  out.order.reserve(size_t(w) * h);
  std::vector<uint8_t> seen(size_t(w) * h);
  const int dx = ((p % w) + w) % w, dy = ((q % h) + h) % h;
  for (int y0 = 0; y0 < h; ++y0)
    for (int x0 = 0; x0 < w; ++x0) {
      if (seen[size_t(y0) * w + x0]) continue;
      out.start.push_back(out.order.size());
      int x = x0, y = y0;
      do {
        seen[size_t(y) * w + x] = 1;
        out.order.push_back(uint32_t(size_t(y) * w + x));
        x += dx;
        if (x >= w) x -= w;
        y += dy;
        if (y >= h) y -= h;
      } while (x != x0 || y != y0);
    }
  out.start.push_back(out.order.size());
  return out;
}

// One line's samples, unrolled past its end by the reach of the widest cone so every apex sees
// as far ahead as its cone can: sample k is texel texels[k / sub mod count] moved k mod sub
// sub-steps along the line. A sub-step lands on the texel column (or row) `whole` texels over
// and `part` of the way to the next row (or column): one linear blend of two texels, which is
// what the GPU's bilinear filter gives there.
void sample_line(const DepthSampler& depth, const ConeScanDirection& dir, const uint32_t* texels,
                 size_t count, size_t reach, std::vector<float>& h) {
  const size_t samples = count * size_t(dir.sub) + reach;
  h.resize(samples);
  // Per sub-step: the texel it starts from, relative to the line's texel, and how far along.
  struct SubStep {
    int dx, dy;
    float part;
  };
  const bool x_major = std::abs(dir.p) == dir.sub;
  std::vector<SubStep> steps(size_t(dir.sub));
  for (int s = 0; s < dir.sub; ++s) {
    const int along = s * (x_major ? dir.q : dir.p);  // across the major axis, in 1 / sub texels
    const int whole = along >= 0 ? along / dir.sub : -((-along + dir.sub - 1) / dir.sub);
    const int major = s * (x_major ? (dir.p > 0 ? 1 : -1) : (dir.q > 0 ? 1 : -1));
    steps[size_t(s)] = {x_major ? major : whole, x_major ? whole : major,
                        float(along - whole * dir.sub) / float(dir.sub)};
  }
  const int next_x = x_major ? 0 : 1, next_y = x_major ? 1 : 0;  // the other texel of a blend
  size_t k = 0;
  for (size_t c = 0; k < samples; c = c + 1 == count ? 0 : c + 1) {
    const int tx = int(texels[c] % uint32_t(depth.w)), ty = int(texels[c] / uint32_t(depth.w));
    h[k++] = depth.d[texels[c]];
    for (int s = 1; s < dir.sub && k < samples; ++s, ++k) {
      const SubStep& st = steps[size_t(s)];
      const float a = depth.at(tx + st.dx, ty + st.dy);
      const float b = depth.at(tx + st.dx + next_x, ty + st.dy + next_y);
      h[k] = a + (b - a) * st.part;
    }
  }
}

// Conservative cones along one line: every sample above the apex narrows it. The steepest rise
// from the apex to any sample ahead touches the upper hull (in position, -depth) of the samples
// ahead; swept from the far end with the hull as a stack, each apex finds it in amortised
// constant time (Graham's scan). Returns, per texel of the line, the least samples across per
// unit of depth rise (+infinity when nothing ahead is higher).
void conservative_along_line(const std::vector<float>& h, int sub, size_t apexes,
                             std::vector<glm::dvec2>& hull, std::vector<float>& across) {
  hull.clear();
  across.assign(apexes, std::numeric_limits<float>::infinity());
  for (size_t k = h.size(); k-- > 0;) {
    const glm::dvec2 here(double(k), -double(h[k]));
    while (hull.size() >= 2) {
      const glm::dvec2 u = hull[hull.size() - 1] - here, v = hull[hull.size() - 2] - here;
      if (u.x * v.y - u.y * v.x < 0) break;  // the nearer point is above the line to the farther
      hull.pop_back();
    }
    if (k < apexes * size_t(sub) && k % size_t(sub) == 0 && !hull.empty()) {
      const glm::dvec2 to = hull.back() - here;
      if (to.y > 0) across[k / size_t(sub)] = float(to.x / to.y);
    }
    hull.push_back(here);
  }
}

// How much wider than the cone found so far a block's bound must be before the scan steps over
// it: rounding in the bound's arithmetic must never hide a segment that narrows the cone by an
// ulp. Without it the map depended, at the last bit of a few texels, on the order the cores
// took the directions in (the bound a scan starts from is the narrowest cone found so far).
constexpr float kSkipSlack = 1.0f + 1e-5f;

// Relaxed cones along one line. Segment k (samples k - 1 to k, depth linear on it) keeps the cone
// out of both its ends when the ray from the top point above the apex leaves the surface there:
// when h / n rises across it, n the distance from the apex in samples. Scanned forward per apex
// until nothing farther can narrow the cone, stepping over aligned blocks of segments whose
// highest candidate end cannot (`block_min[l]`: per block of 2^l segments, the least depth of the
// near end of those that descend along the line; only a descending segment can pass the test),
// or none of which this apex's ray can leave yet (`block_exit[l]`).
struct RelaxedLineScan {
  std::vector<std::vector<float>> block_min;  // levels below kGroupLevel left empty
  // Per block, the apex position from which on none of its segments is left, whatever the
  // cone (the largest relaxed_segment_left_only_before of its segments).
  std::vector<std::vector<int32_t>> block_exit;

  void build(const std::vector<float>& h) {
    const float none = std::numeric_limits<float>::infinity();
    size_t levels = 1;
    while ((size_t(1) << levels) < h.size() && levels < 16) ++levels;
    block_min.resize(levels);                   // each level's storage is reused from line to line
    if (levels <= size_t(kGroupLevel)) return;  // the scan tests every segment
    // Blocks smaller than a group are never stepped over (narrow_group), so the first level
    // kept is the groups', taken from the samples themselves.
    block_exit.resize(levels);
    std::vector<float>& groups = block_min[size_t(kGroupLevel)];
    std::vector<int32_t>& group_exit = block_exit[size_t(kGroupLevel)];
    groups.resize((h.size() + kGroup - 1) / kGroup);
    group_exit.resize(groups.size());
    for (size_t b = 0; b < groups.size(); ++b) {
      float least = none;
      int32_t latest = kNeverLeft;
      for (size_t k = std::max<size_t>(1, b * kGroup); k < std::min(h.size(), (b + 1) * kGroup);
           ++k)
        if (h[k] > h[k - 1]) {
          least = std::min(least, h[k - 1]);
          latest = std::max(latest, exit_from(h, k));
        }
      groups[b] = least;
      group_exit[b] = latest;
    }
    for (size_t l = size_t(kGroupLevel) + 1; l < levels; ++l) {
      coarsen(block_min[l - 1], block_min[l], [](float a, float b) { return std::min(a, b); });
      coarsen(block_exit[l - 1], block_exit[l],
              [](int32_t a, int32_t b) { return std::max(a, b); });
    }
  }

  // Each pair of blocks of `finer` combined into one of `coarser`; an odd last one kept.
  template <class T, class Combine>
  static void coarsen(const std::vector<T>& finer, std::vector<T>& coarser, Combine combine) {
    coarser.resize((finer.size() + 1) / 2);
    for (size_t b = 0; b + 1 < finer.size(); b += 2)
      coarser[b / 2] = combine(finer[b], finer[b + 1]);
    if (finer.size() % 2) coarser.back() = finer.back();
  }

  static constexpr int32_t kNeverLeft = std::numeric_limits<int32_t>::min();  // no segment

  // The position at and past which no apex is left across segment k.
  static int32_t exit_from(const std::vector<float>& h, size_t k) {
    return relaxed_segment_left_only_before(h[k - 1], h[k], k);
  }

  // The least samples across per unit of depth rise for the apex at sample i, from `widest`.
  // `hint` is a segment that narrowed a neighbour's cone (0 for none); tried first, it narrows
  // the bound before the scan starts, so far more blocks are stepped over. On return: the
  // segment that narrowed this cone most (unchanged if none did).
  float across(const std::vector<float>& h, size_t i, float widest, size_t& hint) const {
    const float apex = h[i];
    float best = widest;
    if (hint >= i + 2 && hint < h.size()) narrow(h, i, hint, apex, best, hint);
    const int top = int(block_min.size()) - 1;
    for (size_t k = i + 2; k < h.size() && float(k - 1 - i) < best * apex * kSkipSlack;) {
      // Step over the largest block starting at k that cannot narrow the cone.
      const float near = float(k - 1 - i);  // no candidate end in a block at k is nearer
      int l = std::min(top, __builtin_ctzll(k));
      for (; l >= kGroupLevel; --l) {
        if (block_exit[size_t(l)][k >> l] <= int64_t(i)) break;  // no segment in it is left
        const float m = block_min[size_t(l)][k >> l];
        if (m >= apex || near >= best * (apex - m) * kSkipSlack) break;
      }
      if (l >= kGroupLevel) {
        k += size_t(1) << l;
        continue;
      }
      // Else the segments from k to the end of k's group, tested together.
      k = narrow_group(h, i, k, apex, best, hint);
    }
    return best;
  }

  // Blocks of 2^kGroupLevel segments that are not stepped over are tested lane by lane at once:
  // smaller blocks' bounds cost as much to test as the segments.
  static constexpr int kGroupLevel = 2;
  static constexpr size_t kGroup = size_t(1) << kGroupLevel;

  // narrow() for segments k .. the last of k's aligned group of kGroup, all lanes at once with
  // the scalar arithmetic (the same bits); returns the segment after them. The line's first
  // group (whose lane 0 has no sample before it) and a group reaching past the line's end are
  // left to the scalar test.
  static size_t narrow_group(const std::vector<float>& h, size_t i, size_t k, float apex,
                             float& best, size_t& narrowest) {
    const size_t base = k & ~(kGroup - 1), end = base + kGroup;
    if (base == 0 || end > h.size()) {
      for (; k < h.size() && k < end; ++k) narrow(h, i, k, apex, best, narrowest);
      return k;
    }
    using Lanes = float __attribute__((vector_size(kGroup * sizeof(float))));
    using LaneInts = int32_t __attribute__((vector_size(kGroup * sizeof(int32_t))));
    static_assert(kGroup == 4, "one initialiser per lane");
    const LaneInts lane = {0, 1, 2, 3};
    Lanes at, before;  // h at each lane's segment end and start
    std::memcpy(&at, h.data() + base, sizeof at);
    std::memcpy(&before, h.data() + base - 1, sizeof before);
    const Lanes n = __builtin_convertvector(int32_t(base - i) + lane, Lanes);
    const Lanes inf = Lanes{} + std::numeric_limits<float>::infinity();
    const Lanes at_end = at < apex ? n / (apex - at) : inf;
    const Lanes at_start = before < apex ? (n - 1) / (apex - before) : inf;
    const Lanes least = at_start < at_end ? at_start : at_end;  // std::min(at_end, at_start)
    const LaneInts leaves = (at * (n - 1) > (before + kRelaxedTie) * n) &
                            (lane >= int32_t(k - base));  // lanes before k are not asked
    const Lanes found = leaves ? least : inf;
    for (size_t j = 0; j < kGroup; ++j)  // in order: the first of equal candidates is named
      if (found[j] < best) {
        best = found[j];
        narrowest = base + j;
      }
    return end;
  }

  // Segment k's constraint on the apex at sample i (depth `apex`): both its ends, if the ray from
  // the top point leaves the surface across it (h / n rises by more than kRelaxedTie: a surface
  // along the ray through the top point, h / n constant, is not left, however floats round the
  // blend).
  static void narrow(const std::vector<float>& h, size_t i, size_t k, float apex, float& best,
                     size_t& narrowest) {
    const float hk = h[k], hp = h[k - 1];
    const float n = float(k - i);
    if (!relaxed_segment_leaves(hp, hk, n)) return;
    const float at_end = hk < apex ? n / (apex - hk) : best;
    const float at_start = hp < apex ? (n - 1) / (apex - hp) : best;
    if (std::min(at_end, at_start) < best) {
      best = std::min(at_end, at_start);
      narrowest = k;
    }
  }
};

// A conservative cone may hold no surface point, so every texel centre within kNearTexels is held
// out exactly as well. The lines reach every near texel centre only when the directions include
// its step (32 or more: every primitive step up to 3); with fewer, and before the line sweeps
// (whose per-texel scan missed the diagonal neighbours, caught by the brute-force test), the
// samples between texel centres ran lower than the texels they passed.
void hold_out_near_texel_centres(const ReliefMap& map, int side, std::vector<float>& ratio) {
  constexpr int kNearTexels = 3, kSpan = 2 * kNearTexels + 1;
  double distance[kSpan * kSpan];
  for (int dy = -kNearTexels; dy <= kNearTexels; ++dy)
    for (int dx = -kNearTexels; dx <= kNearTexels; ++dx)
      distance[(dy + kNearTexels) * kSpan + dx + kNearTexels] = std::hypot(dx, dy);
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
              ratio[i] = std::min(
                  ratio[i], float(distance[size_t((dy + kNearTexels) * kSpan + dx + kNearTexels)] /
                                  (rise * side)));
            }
        }
      },
      256);
}

// A texel's cone so far, shared by the cores: each reads the narrowest any has found (a stale
// value only widens its bound) and narrows it without losing another core's narrower one.
float cone_so_far(std::vector<float>& ratio, uint32_t texel) {
  return std::atomic_ref<float>(ratio[texel]).load(std::memory_order_relaxed);
}
void narrow_cone(std::vector<float>& ratio, uint32_t texel, float to) {
  std::atomic_ref<float> cone(ratio[texel]);
  float now = cone.load(std::memory_order_relaxed);
  while (to < now && !cone.compare_exchange_weak(now, to, std::memory_order_relaxed)) {
  }
}

// What one direction's lines are scanned with, kept from line to line.
struct LineScratch {
  std::vector<float> h, reversed, across;
  std::vector<uint32_t> reversed_texels;
  std::vector<glm::dvec2> hull;
  RelaxedLineScan scan;
};

// Narrows `ratio` (per texel, per longer side) by the cones one line's samples `h` find for
// its texels (texel t at sample t * sub), `step` texels apart; `widest` is the options' cap in
// samples per depth.
void narrow_along_line(const std::vector<float>& h, const uint32_t* texels, size_t count, int sub,
                       float step, float side, float widest, bool relaxed,
                       std::vector<float>& ratio, LineScratch& s) {
  std::vector<float>& across = s.across;
  if (relaxed) {
    s.scan.build(h);
    across.resize(count);
    size_t hint = 0;  // the segment that narrowed the next texel's cone along the line
    for (size_t t = count; t-- > 0;) {
      const size_t i = t * size_t(sub);
      const float bound = std::min(widest, cone_so_far(ratio, texels[t]) * side / step);
      const float found = h[i] > 0.0f ? s.scan.across(h, i, bound, hint) : bound;
      across[t] = found < bound ? found : std::numeric_limits<float>::infinity();
    }
  } else {
    conservative_along_line(h, sub, count, s.hull, across);
  }
  for (size_t t = 0; t < count; ++t)  // +infinity: not narrowed here
    if (across[t] < widest) narrow_cone(ratio, texels[t], float(double(across[t]) * step / side));
}

// Narrows `ratio` by the cones found along one direction's lines, and with `both_ways` along
// the opposite direction's too. The opposite direction's lines are the same cycles of texels,
// and its samples are these in reverse: the same points, each blended from the same two texels
// by the same weight (sample_line's whole texels and parts are the same integers from either
// end), so they are read once. Its reach is the one found before this direction narrowed any
// cone: as far or farther than it needs.
void narrow_along_direction(const DepthSampler& depth, const ConeScanDirection& dir,
                            const ConeMapOptions& o, bool both_ways, std::vector<float>& ratio) {
  const Lines lines = lines_along(depth.w, depth.h, dir.p, dir.q);
  const float side = float(std::max(depth.w, depth.h));
  const float step = dir.step_texels();  // once: a hypot per texel was 14% of the sweep's time
  const float widest = float(o.max_ratio) * side / step;  // samples per depth
  LineScratch s;
  for (size_t l = 0; l + 1 < lines.start.size(); ++l) {
    const uint32_t* texels = lines.order.data() + lines.start[l];
    const size_t count = lines.start[l + 1] - lines.start[l];
    // The cone is the narrowest over directions, so only a cone narrower than the directions
    // before found matters: that bound, times the apex's depth, is as far as anything can
    // narrow it. Unroll the line that far past its end.
    float reach = 0;
    for (size_t t = 0; t < count; ++t)
      reach = std::max(reach, std::min(widest, cone_so_far(ratio, texels[t]) * side / step) *
                                  depth.d[texels[t]]);
    sample_line(depth, dir, texels, count, size_t(std::ceil(reach)) + 2, s.h);
    narrow_along_line(s.h, texels, count, dir.sub, step, side, widest, o.relaxed, ratio, s);
    if (!both_ways) continue;
    const size_t period = count * size_t(dir.sub);
    s.reversed.resize(s.h.size());
    s.reversed[0] = s.h[0];
    for (size_t k = 1; k < period; ++k) s.reversed[k] = s.h[period - k];
    for (size_t k = period; k < s.reversed.size(); ++k) s.reversed[k] = s.reversed[k - period];
    s.reversed_texels.resize(count);
    for (size_t t = 0; t < count; ++t) s.reversed_texels[t] = texels[(count - t) % count];
    narrow_along_line(s.reversed, s.reversed_texels.data(), count, dir.sub, step, side, widest,
                      o.relaxed, ratio, s);
  }
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
  // Directions handed out one at a time to whichever core is free (their costs differ by up
  // to 2x: interleaving them into fixed groups left one core idle for a fifth of the time);
  // the cores narrow one map together, so each direction's scan starts from the narrowest
  // cones any core has found so far. A cone is the narrowest over directions whatever their
  // order, bit for bit (kSkipSlack): a direction's scan only stops early at that bound.
  // A direction and its opposite are one task, their lines read once.
  const std::vector<ConeScanDirection> dirs = cone_scan_directions(o.directions);
  struct Task {
    size_t direction;
    bool both_ways;
  };
  std::vector<Task> tasks;
  for (size_t d = 0; d < dirs.size(); ++d) {
    const auto opposite = std::find_if(dirs.begin(), dirs.end(), [&](const ConeScanDirection& e) {
      return e.p == -dirs[d].p && e.q == -dirs[d].q;
    });
    const size_t o_d = size_t(opposite - dirs.begin());
    if (o_d == dirs.size() || o_d > d) tasks.push_back({d, o_d < dirs.size()});
  }
  out.ratio.assign(size_t(map.width) * map.height, float(o.max_ratio));
  parallel_for_workers(
      tasks.size(),
      [&](size_t, size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i)
          narrow_along_direction(depth, dirs[tasks[i].direction], o, tasks[i].both_ways, out.ratio);
      },
      1);
  if (!o.relaxed) hold_out_near_texel_centres(map, std::max(map.width, map.height), out.ratio);
  out.compute_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

ConeMap compute_cone_map_in_order(const ReliefMap& map, const ConeMapOptions& o,
                                  const std::vector<size_t>& order) {
  const DepthSampler depth(map);
  const std::vector<ConeScanDirection> dirs = cone_scan_directions(o.directions);
  ConeMap out;
  out.width = map.width;
  out.height = map.height;
  out.ratio.assign(size_t(map.width) * map.height, float(o.max_ratio));
  for (size_t d : order) narrow_along_direction(depth, dirs.at(d), o, false, out.ratio);
  if (!o.relaxed) hold_out_near_texel_centres(map, std::max(map.width, map.height), out.ratio);
  return out;
}

ConeMap cached_cone_map(const ReliefMap& map, const ConeMapOptions& o) {
  // Bump when compute_cone_map changes its answers (5: the scan's slack for rounding; before it
  // a few texels could differ by an ulp from run to run).
  constexpr int kAlgorithmVersion = 5;
  char options[128];
  std::snprintf(options, sizeof options, "v%d|%d|%d|%.9g|", kAlgorithmVersion, int(o.relaxed),
                o.directions, o.max_ratio);
  return cached_precompute("cone_map", options, map.width, map.height, map.content_hash(),
                           &ConeMap::ratio, [&] { return compute_cone_map(map, o); });
}

}  // namespace rl
