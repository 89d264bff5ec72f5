#pragma once
// The truth of a multilayer map itself (the "sampled" level for non-height-field relief): the
// solid its layers describe under nearest sampling -- in each texel's column, the depths
// between layer 0 and 1, 2 and 3, ... (and below the last layer of an odd count) -- traced
// exactly by walking the texel columns a ray crosses. Against it a technique's error is its
// search error alone; against the pattern mesh (MeshTruth) it also includes the
// representation's. A hit shades with the stored normal and colour of the layer whose depth
// is nearest the hit (the layer choice of the paper's Appendix A), like the technique.
#include <vector>

#include "relief/relief_map.h"
#include "truth/truth_surface.h"

namespace rl {

class LayersTruth final : public TruthSurface {
 public:
  // `map` must have layers (the config refuses truth = "layers" otherwise). `tiled`: the map
  // repeats (GL_REPEAT, a pattern); otherwise it is one object in its box (an impostor) and outside
  // the box there is nothing.
  explicit LayersTruth(const ReliefMap& map, bool tiled = true);

  TruthHit intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                     double t_max) const override;
  bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                double t_max) const override;
  float max_depth() const override { return 1.0f; }
  double tessellation_bound() const override { return 0.0; }  // exact for nearest sampling
  double rounding_bound() const override { return kDoubleRounding; }
  double build_ms() const override { return 0.0; }

 private:
  // First point of the column solid of texel (i, j) on the ray for t in [t0, t1].
  bool column_hit(long i, long j, const glm::dvec3& o, const glm::dvec3& d, double t0, double t1,
                  TruthHit& hit) const;
  TruthHit trace(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                 double t_max) const;

  int width_ = 0, height_ = 0, count_ = 0;
  bool tiled_ = true;
  std::vector<float> depth_;  // [layer * texels + texel], unused = 1
  std::vector<glm::vec3> normal_, color_;
};

}  // namespace rl
