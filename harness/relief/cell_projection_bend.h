#pragma once
// Apaza & Andujar, Figure 3: "The axial parameterization maps straight line segments onto
// planar curves", where the parallel, planar and perspective projections map them onto
// segments (Section 3.2: "the first three types of projections define linear mappings").
// Measured on a complex's own mesh: every mesh edge is cut at the grid's cell boundaries, and
// each piece inside a grey cell that projects onto one domain face is sampled along its length;
// its bend is the largest distance of the projected samples from the chord between its
// projected ends, in texels of that face. Section 3.3.2's geometry shader subdivides edges in
// axial cells for this reason; the CPU construction here samples each texel's projection line
// and needs no subdivision.
#include <array>

#include "relief/cell_complex.h"

namespace rl {

struct ProjectionBend {
  // Indexed by CellProjection::Type: pieces measured, their largest and mean bend (texels).
  std::array<long, 4> pieces{};
  std::array<double, 4> max_texels{}, mean_texels{};
};

// `samples`: points per piece beyond its two ends.
ProjectionBend projection_bend(const CellComplex& cc, int samples = 15);

}  // namespace rl
