#pragma once
// Cone maps for cone step mapping: per texel, the ratio (across per unit of depth) of an upward
// cone with its apex on the surface point at the texel's centre. Across is measured in texels
// (square in the world: the harness keeps texels square) and stored in units of the longer
// side (texture units on a square map).
//
// Conservative (Dummer 2006): the widest cone holding no surface point, so a ray inside it
// can step to its boundary without meeting the surface.
//
// Relaxed (Policarpo & Oliveira, GPU Gems 3 chapter 18): the widest cone such that a ray from
// the top point above the apex (depth 0) towards any surface point, continued until it leaves
// the surface, leaves it below the cone. A ray that steps to the cone's boundary may then
// have entered the surface, but crossed it only once: the binary search that follows finds
// the crossing. Along a ray z = m x from the top point (x across, z depth), the points where
// it leaves the surface h are those where h(x) / x rises; the cone must keep them out.
//
// Computed on the CPU, multithreaded, along lines through texel centres in rational
// directions (cone_scan_directions below; the surface sampled bilinearly, as the GPU sees it):
// every texel on a line shares the line's samples. Conservative cones take the steepest rise
// from each apex to the upper hull of the samples ahead (one hull sweep per line); relaxed
// cones scan ahead of each apex only until nothing farther could narrow the cone (distance /
// apex depth >= the ratio found), stepping over blocks of segments that cannot.
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "relief/relief_map.h"

namespace rl {

// A direction the precompute scans: the primitive step (p, q) from one texel centre to the next
// on its line, sampled `sub` = max(|p|, |q|) times per step, so every sample lies on a texel
// column (|p| = sub) or row (|q| = sub) and is one linear blend of two texels. Every texel on a
// line shares the line's samples: a direction costs one pass per line, not a scan per texel.
struct ConeScanDirection {
  int p, q, sub;
  float step_texels() const { return float(std::hypot(p, q) / sub); }  // between samples
};

// Every primitive step with max(|p|, |q|) <= m, for the least m giving at least `at_least`
// directions (8 at m = 1; 16, 32, 48, 80, 96, 144, 176, 224, 256 at m = 2 .. 10), cheapest first.
// 32 (m = 3) leaves gaps of up to 18.4 degrees between directions, 80 (m = 5) up to 11.3.
std::vector<ConeScanDirection> cone_scan_directions(int at_least);

struct ConeMapOptions {
  bool relaxed = true;
  int directions = 32;     // at least this many directions (cone_scan_directions)
  double max_ratio = 1.0;  // cap, texture units per unit of depth (GPU Gems 3 stores <= 1)
};

struct ConeMap {
  int width = 0, height = 0;
  std::vector<float> ratio;  // texels, row 0 at v = 0.5 / height
  double compute_ms = 0;
  bool from_cache = false;
};

ConeMap compute_cone_map(const ReliefMap& map, const ConeMapOptions& options);

// The same on one core, the directions taken one after another in `order` (indices into
// cone_scan_directions(options.directions)): the same map, bit for bit, whatever the order
// (tests hold it to that; compute_cone_map's cores take the directions in whatever order
// they come free).
ConeMap compute_cone_map_in_order(const ReliefMap& map, const ConeMapOptions& options,
                                  const std::vector<size_t>& order);

// The relaxed test of one segment (samples k - 1 to k, depths h_start to h_end): the ray from
// the top point above an apex n samples before k leaves the surface across it when h / n rises
// by more than a tie, in float as the scan computes it (a surface along the ray is not left,
// however floats round a blend).
constexpr float kRelaxedTie = 1e-6f;
inline bool relaxed_segment_leaves(float h_start, float h_end, float n) {
  return h_end * (n - 1) > (h_start + kRelaxedTie) * n;
}

// The apex position from which on segment k is never left: for every apex at sample i >= the
// returned value (n = k - i), relaxed_segment_leaves(h_start, h_end, n) is false; INT32_MIN
// when it is false for every apex. The scan steps over a block whose segments all give i or less.
// With d = h_start + kRelaxedTie as the test rounds it, h_end (n - 1) <= d n holds exactly for n <=
// h_end / (h_end - d), and rounding each product to float keeps their order, so the test fails
// there; one sample more covers the rounding of that quotient in double
// (ConeMap.RelaxedSegmentBoundHoldsEverywhere).
inline int32_t relaxed_segment_left_only_before(float h_start, float h_end, size_t k) {
  const float d = h_start + kRelaxedTie;
  if (!(h_end > d)) return std::numeric_limits<int32_t>::min();
  const double lag = double(h_end) / (double(h_end) - double(d));
  return int32_t(std::ceil(double(k) - lag)) + 1;
}

// The ratios the shader reads through GL_LINEAR: each texel's the least over its 3 x 3
// neighbourhood (wrapping), so the ratio interpolated anywhere in a cell is no wider than the
// narrowest of the cones at its four corners. Interpolating the raw ratios is not conservative:
// between a narrow cone next to a cliff and a wide one a texel away the blend is wider than the
// cone the point needs, and grazing rays stepped over whole walls (up to 100 texels on the
// contract's tilted planes and saddle, conservative and relaxed cones alike).
std::vector<float> ratios_safe_under_filtering(const ConeMap& cones);
// compute_cone_map through the precompute cache (core/precompute_cache.h).
ConeMap cached_cone_map(const ReliefMap& map, const ConeMapOptions& options);

}  // namespace rl
