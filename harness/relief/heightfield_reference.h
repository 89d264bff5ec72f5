#pragma once
// Double-precision reference intersection of a ray with the bilinearly reconstructed
// heightfield (the surface GL_LINEAR + GL_REPEAT sampling of the depth map defines).
// Walks the texel cells under the ray (2D DDA between texel centres) and, in each cell,
// solves the ray against the bilinear patch exactly: the depth along the ray is a quadratic in t.
// Used by ray-probe tests as the ground truth of every single-layer search.
#include <glm/glm.hpp>

#include "relief/relief_map.h"

namespace rl {

struct ReferenceHit {
  bool hit = false;
  double t = 0;      // ray parameter of the first point with ray depth >= surface depth
  glm::dvec2 uv{0};  // texture coordinate at t
  double depth = 0;  // ray depth at t (equals the surface depth there)
  long cells = 0;    // texel cells visited
};

// Ray: (uv, depth)(t) = origin + t * direction, t in [0, t_max]. Depth grows downward; the
// map surface is depth d(u, v) in [0, 1]. Returns the first t where the ray is at or below
// the surface. Rays with direction.z <= 0 that never go below the surface miss.
// Smallest root of a t^2 + b t + c = 0 in [lo, hi] (numerically stable pair; a tangency lost
// to rounding counts as a double root), or NaN.
double smallest_root_in(double a, double b, double c, double lo, double hi);

// One bilinear patch against a ray segment. The patch has depths d00, d10, d01, d11 at the
// corners of its unit cell; the segment starts at cell coordinates (x, y), depth z, and moves
// by (dx, dy, dz) per unit of s. Returns the first s in [0, span] at which the ray is at or
// below the patch, or NaN. Working from the segment's own start keeps every coefficient of
// the quadratic of order one, however far along the ray the cell lies.
double bilinear_patch_hit(double d00, double d10, double d01, double d11, double x, double y,
                          double z, double dx, double dy, double dz, double span);

ReferenceHit intersect_heightfield(const ReliefMap& map, const glm::dvec3& origin,
                                   const glm::dvec3& direction, double t_max);

// The same ray against the map sampled with GL_NEAREST: each texel a flat-topped column of its
// depth (what the multilayer and double-depth searches read, in their single-layer case).
ReferenceHit intersect_texel_columns(const ReliefMap& map, const glm::dvec3& origin,
                                     const glm::dvec3& direction, double t_max);

}  // namespace rl
