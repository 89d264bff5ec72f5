#pragma once
// The 4D texture of omni-directional displacement maps (chapter 5, "Omni-directional
// displacement maps", Figures 5.29-5.32): per super pixel (x, y) of a tile of the surface and
// per direction (a, b), the first hit of a ray cast from the super pixel's centre on the
// calculation plane (depth 0, the top of the relief) into the tileable surface, in the
// direction R = (cos a sin b, cos b, sin a sin b) of the chapter's formulas (tangent space:
// x along u, y along v, z into the surface; a, b in [0, pi]). Directions are stored at the
// centres of an A x B grid of (a, b): a_k = pi (k + 0.5) / A.
//
// The 4D map is laid out in one 2D texture in either order of Figures 5.31-5.32: direction-
// major (a, b, x, y): A x B tiles, each the X x Y image of one direction; or spatial-major
// (x, y, a, b): X x Y super pixels, each the A x B directions seen from one point.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "relief/relief_map.h"

namespace rl {

// Where the stored rays start: just above the top (depth 0) -- a ray starting exactly on a
// plateau at depth 0 would slip into the solid past the coincident triangle (Embree reports no
// hit at t = 0), so a brick wall drew as noise.
inline constexpr double kOddStartDepth = -1e-3;

struct OddSize {
  int spatial = 32;     // super pixels per tile side (X = Y)
  int directions = 16;  // directions per angle (A = B)
  bool operator==(const OddSize& o) const {
    return spatial == o.spatial && directions == o.directions;
  }
};

struct OddMap {
  OddSize size;
  bool direction_major = true;
  // depth_aspect: world relief depth / world length of one unit of u (.x) and of v (.y): the
  // directions are the world's, traced in the map's texture space.
  glm::dvec2 depth_aspect{1.0};
  int width = 0, height = 0;      // the 2D texture: X * A by Y * B
  std::vector<glm::vec4> texels;  // rgb: tangent normal * 0.5 + 0.5; a: the hit's depth
  long missed_rays = 0;           // rays that left the relief without a hit (stored at depth 1)

  // The chapter's direction of grid cell (ka, kb), unit length, z into the surface.
  static glm::dvec3 direction(double a, double b);
  glm::dvec3 stored_direction(int ka, int kb) const;
  // The continuous (a, b) / pi in [0, 1]^2 of a direction (z into the surface) by the chapter's
  // formulas a = acos(A / sqrt(1 - B^2)), b = acos(B) with A = T.V, B = B.V, the cosines
  // clamped to [-1, 1] (rounding pushes them past it at a = 0 or pi); a = 1/2 where
  // sqrt(1 - B^2) vanishes (V along the binormal: every a is the same direction).
  static glm::dvec2 angles(const glm::dvec3& v);
  // Texel index of super pixel (x, y) and direction (ka, kb) in the layout.
  size_t index(int x, int y, int ka, int kb) const;
  size_t bytes() const { return size_t(width) * height * 4; }  // as uploaded: RGBA8
};

// Casts the X Y A B rays into `map` (bilinear, tiled, solid floor) with Embree.
OddMap build_odd_map(const ReliefMap& map, OddSize size, bool direction_major,
                     glm::dvec2 depth_aspect);

}  // namespace rl
