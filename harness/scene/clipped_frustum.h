#pragma once
// Baboud & Decoret 2006, Section 4.1, "Clipped frustum": a reverse-perspective heightfield is
// drawn by its frustum, typically much larger than what it holds, so many fragments shade rays
// that meet nothing. Cutting the relief's bounding box out of the frustum "is done as a
// preprocess, does not change the shader at all": the faces of frustum ∩ box, in the box's
// affine coordinates, which the shader projects as it projects the frustum's.
#include <vector>

#include <glm/glm.hpp>

#include "relief/relief_map.h"
#include "relief/reverse_projection.h"

namespace rl {

struct AffineBox {
  glm::dvec3 lo{0.0}, hi{1.0};
};

// The affine bounding box of everything the map's heightfield can put in the way of a ray:
// each texel's column from its surface down to depth 1 (the floor, or the extruded solid
// above an empty one), its footprint widened by a texel each way for the bilinear cells it
// shares with its neighbours. With an empty floor, texels at depth 1 hold nothing. False when
// no texel holds anything.
bool relief_affine_bounds(const ReliefMap& map, const ReverseProjection& projection,
                          bool empty_floor, AffineBox& box);

// The boundary of the frustum (the texture box [0, 1]^3 mapped to affine space) intersected
// with `box`, as convex polygons in affine coordinates, wound as the box proxy's faces:
// counter-clockwise seen from outside in world space, where depth runs downwards.
std::vector<std::vector<glm::dvec3>> clipped_frustum_faces(const ReverseProjection& projection,
                                                           const AffineBox& box);

}  // namespace rl
