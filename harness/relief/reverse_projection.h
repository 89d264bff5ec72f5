#pragma once
#include <glm/glm.hpp>

namespace rl {

// Reverse-perspective texture space (Baboud & Decoret, Section 4). Maps the box's affine
// coordinates a = (x, y, z) in [0, 1]^3 (PlanarBase's texture space, z = depth) to the
// relief's texture space projectively, with the centre of projection at depth `cop` > 1 under
// the box's centre: lines stay lines, so every search runs unchanged in texture space, while
// the box becomes a frustum narrowing downwards (the paper's inverted frustum) and a bake
// along its rays sees the sides of an object. cop = 0: the identity (orthographic).
struct ReverseProjection {
  double cop = 0;
  bool active() const { return cop > 1; }
  glm::dvec3 texture_from_affine(const glm::dvec3& a) const {
    if (!active()) return a;
    const double k = cop / (cop - a.z);
    return {0.5 + (a.x - 0.5) * k, 0.5 + (a.y - 0.5) * k, a.z * (cop - 1) / (cop - a.z)};
  }
  glm::dvec3 affine_from_texture(const glm::dvec3& t) const {
    if (!active()) return t;
    const double z = t.z * cop / (cop - 1 + t.z);
    const double k = (cop - z) / cop;
    return {0.5 + (t.x - 0.5) * k, 0.5 + (t.y - 0.5) * k, z};
  }
};

}  // namespace rl
