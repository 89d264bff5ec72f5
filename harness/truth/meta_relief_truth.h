#pragma once
// Truth of a meta-relief (relief/meta_relief.h): the surface Eq. 2 defines, the weighted sum of
// every layer's bilinear depth at its own tiling and resolution, fractional tilings included.
//
// Traced exactly rather than tessellated: between the crease lines of all the layers' texel
// grids (their union, walked by one 2D DDA per layer, the next crossing being the nearest of
// any layer's), every layer is one bilinear patch, so the depth along the ray is one quadratic
// in t per union cell, solved in double precision like the single-map reference
// (relief/heightfield_reference.h). Nothing is built and nothing repeats: a fractional tiling
// (5.5 repeats every 2 base tiles, 3.7 every 10) would make an Embree grid of one common period
// tens of millions of vertices, while this costs one DDA step per crease crossed (and no solve
// where the ray passes above every layer's shallowest corner of the cell). Its deviation
// from the surface is rounding alone (tessellation_bound() = 0); tests/test_meta_relief checks it
// against the Embree heightfield truth where a bake is exact and against dense sampling
// elsewhere.
#include <memory>
#include <vector>

#include "relief/meta_relief.h"
#include "truth/truth_surface.h"

namespace rl {

class MetaReliefTruth final : public TruthSurface {
 public:
  explicit MetaReliefTruth(std::shared_ptr<const MetaRelief> meta);

  TruthHit intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                     double t_max) const override;
  bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                double t_max) const override;
  float max_depth() const override { return float(meta_->max_depth()); }
  double tessellation_bound() const override { return 0.0; }
  double rounding_bound() const override { return kDoubleRounding; }
  double build_ms() const override { return 0.0; }

  // The first t in [t_min, t_max] where the ray is at or below the surface, or NaN; `cells`
  // counts the union cells visited.
  double first_hit(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                   double t_max, long* cells = nullptr) const;

 private:
  std::shared_ptr<const MetaRelief> meta_;
  std::vector<std::vector<float>> depths_;  // per layer, row-major
};

}  // namespace rl
