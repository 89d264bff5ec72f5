#pragma once
// The surface a cell complex's distance maps encode (Apaza & Andujar; relief/cell_complex.h),
// traced on the CPU in the cube's texture space: CellComplex::encoded_inside along the ray, in
// steps of a quarter of a face texel through grey cells (white cells are skipped whole, black
// ones are inside), each sign change refined by bisection to rounding. Against it a
// cell-complex technique's error is its search's alone; against the mesh (MeshTruth), search
// and representation together. Stated tolerance (truth_bound): the step, in cube sides -- two
// crossings closer than it along a ray can both be missed.
#include <memory>

#include "relief/cell_complex.h"
#include "truth/truth_surface.h"

namespace rl {

class CellComplexTruth final : public TruthSurface {
 public:
  explicit CellComplexTruth(std::shared_ptr<const CellComplex> cells);

  TruthHit intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                     double t_max) const override;
  bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                double t_max) const override;
  float max_depth() const override { return 1.0f; }
  double tessellation_bound() const override { return step_; }
  // A crossing it finds is bisected to double rounding: its position is exact. The step bounds
  // only what it can miss (two crossings closer than a step along the ray), not where it hits.
  double vertical_bound() const override { return 0.0; }
  double rounding_bound() const override { return kDoubleRounding; }
  double build_ms() const override { return 0; }

 private:
  TruthHit trace(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                 double t_max) const;  // intersect() without counting the ray
  std::shared_ptr<const CellComplex> cells_;
  double step_ = 0;  // texture units (cube sides)
};

}  // namespace rl
