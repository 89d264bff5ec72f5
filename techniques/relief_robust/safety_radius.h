#pragma once
// Safety radii (Baboud & Decoret 2006, Sections 3.4-3.5): per texel, the number n of
// centerlines a ray may advance from a crossing inside the texel with at most one
// intersection with the heightfield, so a robust search can step by n without skipping a
// feature. Computed on the CPU, multithreaded, and cached on disk.
#include <cstdint>
#include <string>
#include <vector>

#include "profile_criteria.h"
#include "relief/relief_map.h"

namespace rl {

struct SafetyRadiusOptions {
  int directions = 16;  // sampled ray azimuths over 360 degrees
  int starts = 3;       // sweep lines per texel across the ray, 1/starts apart
  double step = 0.5;    // profile sampling step along the major axis, texels; 1/step whole (the
                        // samples must fall on every centerline, where the starts are)
  int max_radius = 0;   // cap in texels; 0 = follow the texture: min(255, larger side)
  double error_allowed = 0.0;  // depth a ray may dip into a feature unseen (Figure 12)
  // Section 3.5 as written: rays blocked by the heightfield before they pass above the texel
  // are ignored (the search never stands on such a ray). false = conservative radii that
  // hold for every ray above the texel, blocked or not (smaller, never unsafe).
  bool ignore_blocked = true;
  // Section 3.5 in its own words: "for each direction, we compute the safety radius and keep the
  // maximum over all directions" — a radius then safe for one direction only. false (the
  // default) keeps the minimum, safe for every sampled direction.
  bool max_over_directions = false;
};

// The cap options.max_radius means for a map (0 = min(255, larger side)).
int effective_max_radius(const ReliefMap& map, const SafetyRadiusOptions& options);

struct SafetyRadii {
  int width = 0, height = 0;
  std::vector<uint8_t> radius;  // texels, row 0 at v = 0.5 / height
  double compute_ms = 0;
  bool from_cache = false;
  // Conservative radii: the starts answered one at a time, only as far as their answer could
  // still lower a radius, rather than with their whole line (0 from the cache).
  long starts_answered_alone = 0;
  int zero_count() const;
};

// The discrete safety radius of every texel: the largest whole number of centerlines a ray
// crossing the texel's centerline above the surface may advance with at most one
// intersection, minimised over the sampled directions and start points.
//
// ignore_blocked (the paper's Section 3.5): only rays that are unblocked from where they
// entered the texture count. For one direction and one line through the map, a descending
// ray above the start x0 that is unblocked behind it, dips below the surface and is back above
// at s2 exists exactly when the "horizon" of (s2, h(s2)) looking back along the line — the
// point before s2 that a line through (s2, h(s2)) rising backwards touches first — lies
// strictly after x0 and above h(s2). (The lowest admissible ray through (s2, h(s2)) must clear
// every point up to x0; it dips under the terrain between x0 and s2 exactly when a point there
// rises above it.) One upper-convex-hull sweep per line gives every sample's horizon, and a
// suffix minimum gives every start's first violation: O(samples) per line, independent of the
// radii. Lines start where they enter the map (nothing behind a map border blocks: exact for
// the box proxy, conservative for tiled bases) and run past its far border, wrapping, for the
// cap, but only until every start of the line has met its first violation. With error_allowed = e,
// points before s2 count e lower (dips of at most e are not seen; rays up to e below the start
// count, conservatively).
//
// Otherwise (conservative): every ray above the start counts, blocked or not. The same lines
// are swept and every start of a line answered at once (first_conservative_violations; with
// error_allowed > 0 each start scans ahead, first_two_hit_after); a texel takes the radii of
// every line within one line spacing of it, so both lines bracketing a crossing bound it. Where
// a line's texels are already small, each start is answered alone instead, only as far as its
// answer could still lower one of them (first_conservative_violation_before): the same radii.
SafetyRadii compute_safety_radii(const ReliefMap& map, const SafetyRadiusOptions& options);

// compute_safety_radii with the conservative radii's shortcuts off: every line answered whole,
// and no radii shared between the first rounds of directions. The same radii, slower: what the
// tests hold the shortcuts to.
SafetyRadii compute_safety_radii_without_shortcuts(const ReliefMap& map,
                                                   const SafetyRadiusOptions& options);

// compute_safety_radii through an on-disk cache keyed by the map's content and the options
// (folder: $RELIEFLAB_CACHE_DIR, else $XDG_CACHE_HOME/relieflab, else ~/.cache/relieflab).
SafetyRadii cached_safety_radii(const ReliefMap& map, const SafetyRadiusOptions& options);

}  // namespace rl
