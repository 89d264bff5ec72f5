#pragma once
// Texture-space ambient occlusion (Limberger, Schetinger & Oliveira, "Meta-relief texture
// mapping with dynamic texture-space ambient occlusion", Section IV-A). Per texel, the horizon
// is searched along `directions` azimuths over the tileable map (toroidal wrap); the edges of
// the visible cone meet the unit hemisphere above the texel, and their orthographic projection
// onto the texture plane is a polygon whose area, relative to the unoccluded one, is the
// texel's visibility (1 = open sky, 0 = fully occluded). That area is the discrete projected
// solid angle: for a horizon elevation theta(phi) the cosine-weighted visible part of the
// hemisphere is 1/2 * integral of cos^2 theta dphi, the area of the polar curve r = cos theta.
//
// One deliberate difference from the paper: it divides the polygon's area by pi; this divides
// by the polygon of an open sky (n/2 sin(2 pi / n)), so that a flat map is exactly 1 rather
// than 0.9974 at n = 50.
#include <cstdint>
#include <string>
#include <vector>

#include "relief/relief_map.h"

namespace rl {

struct AoMapOptions {
  int directions = 50;  // the paper's 50 directions, 7.2 degrees apart
  // The paper's low-pass filter (3 x 3 box, wrapping), applied only to texels with some
  // occlusion so that none is introduced where there was none.
  bool filter = true;
  // World depth of depth 1 over the world width of one texel: how tall the relief is in texels.
  double height_texels = 1.0;
};

struct AoMap {
  int width = 0, height = 0;
  std::vector<float> visibility;  // [0, 1], row 0 at v = 0.5 / height
  double compute_ms = 0;
  bool from_cache = false;
};

// The horizon search per texel, multithreaded on the CPU: the paper's way. Along each direction
// the profile is sampled one texel apart, bilinearly, and the search stops when no point farther
// away could rise above the horizon found so far (the map's highest point is below it), or
// after twice the map's longer side.
AoMap compute_ao_map_march(const ReliefMap& map, const AoMapOptions& options);

// The same horizons for every texel at once, one line sweep per direction
// (relief/horizon_sweep.h): exact over each texel's first two samples, interpolated between
// neighbouring sweep lines beyond. The default; its difference from the march is bounded in
// tests/test_ambient_occlusion.cpp.
AoMap compute_ao_map(const ReliefMap& map, const AoMapOptions& options);

// The paper's low-pass filter: a 3 x 3 box (wrapping) on the texels with some occlusion only,
// so that none is introduced where there was none.
void filter_occluded_texels(const ReliefMap& map, std::vector<float>& visibility);

// Who computes a map: the line sweep on the CPU (compute_ao_map), or another (the march of
// gpu/gpu_ao_map.h in a fragment shader). `name` keys the cache, so the two never read
// each other's files.
struct AoMapMethod {
  const char* name = "cpu";
  AoMap (*compute)(const ReliefMap&, const AoMapOptions&) = compute_ao_map;
};

// `method`'s map through the precompute cache (core/precompute_cache.h).
AoMap cached_ao_map(const ReliefMap& map, const AoMapOptions& options, AoMapMethod method = {});

// Eq. 6: visibility after the relief depth is scaled by s, from the stored value alone. The
// visible cone is taken to be a circular one of radius r = sqrt(ao) on the unit hemisphere
// (Eq. 4); scaling heights by s moves its rim to height s H with H = sqrt(1 - r^2), on a
// hemisphere of radius R' (Eq. 5), and ao' = ao / R'^2. Finite and in [0, 1] for every s >= 0
// (s = 0 with ao = 0, a 0/0, is a flat relief: 1). harness/glsl/ambient_occlusion.glsl is the
// same formula.
double ao_rescaled(double ao, double s);

}  // namespace rl
