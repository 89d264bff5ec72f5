#pragma once
// Safety radii (Baboud & Decoret 2006, Sections 3.4-3.5): per texel, the number n of
// centerlines a ray may advance from a crossing inside the texel with at most one
// intersection with the heightfield, so a robust search can step by n without skipping a
// feature. Computed on the CPU, multithreaded, and cached on disk.
#include <cstdint>
#include <string>
#include <vector>

#include "relief/relief_map.h"

namespace rl {

struct SafetyRadiusOptions {
  int directions = 16;         // sampled ray azimuths over 360 degrees
  int starts = 3;              // sampled crossing points along the texel's centerline
  double step = 0.5;           // profile sampling step, in texels along the major axis
  int max_radius = 16;         // cap, in texels (radii are stored in 8 bits)
  double error_allowed = 0.0;  // depth a ray may dip into a feature unseen (Figure 12)
};

struct SafetyRadii {
  int width = 0, height = 0;
  std::vector<uint8_t> radius;  // texels, row 0 at v = 0.5 / height
  double compute_ms = 0;
  bool from_cache = false;
  int zero_count() const;
};

// The discrete conservative radius of every texel. For each texel, direction and start point
// it walks the height profile forward along the ray's major axis and finds the first
// distance at which a descending ray starting above the surface there could enter and leave
// the surface (two intersections); the radius is the largest whole number of centerlines
// before it, minimised over directions and starts. Rays blocked before the texel are not
// ignored (unlike the paper): radii can only come out smaller, never unsafe.
SafetyRadii compute_safety_radii(const ReliefMap& map, const SafetyRadiusOptions& options);

// compute_safety_radii through an on-disk cache keyed by the map's content and the options
// (folder: $RELIEFLAB_CACHE_DIR, else $XDG_CACHE_HOME/relieflab, else ~/.cache/relieflab).
SafetyRadii cached_safety_radii(const ReliefMap& map, const SafetyRadiusOptions& options);

// The first violation distance of one profile h[0..n) sampled every `step` (heights, up =
// larger), or +infinity: where a descending ray above h[0] could have entered and left.
double first_two_hit_distance(const std::vector<double>& h, double step, double error_allowed);

}  // namespace rl
