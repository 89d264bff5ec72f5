#pragma once
// Embree ground truth of a heightfield relief: the bilinearly reconstructed surface of the
// map (what GL_LINEAR sampling defines), tessellated into an Embree grid whose vertices lie
// exactly on that surface and on every texel-centre crease line. Within one bilinear cell
// f = ... + C x y, so a tessellation of k x k sub-squares deviates from the bilinear surface
// by at most |C| / (4 k^2) depth units; k is chosen per map to meet a stated tolerance.
//
// Space: (u, v, depth), depth growing downward, exactly the shaders' texture space. One tile
// is built; rays walk the tiles they cross (2D DDA over tile cells), so tiling and grazing
// rays cost no memory.
#include <embree3/rtcore.h>

#include "relief/relief_map.h"
#include "truth/truth_surface.h"

namespace rl {

// Largest |C| = |d00 - d10 - d01 + d11| over the map's bilinear cells: the twist that makes a
// bilinear patch non-planar (a k x k tessellation of a cell deviates by |C| / (4 k^2)).
double max_twist(const ReliefMap& map);

class HeightfieldTruth final : public TruthSurface {
 public:
  // `tolerance` in depth units; `max_vertices` caps memory (the achieved bound is reported).
  HeightfieldTruth(const ReliefMap& map, double tolerance = 2e-3, size_t max_vertices = 1u << 24,
                   int forced_subdivision = 0);
  ~HeightfieldTruth();
  HeightfieldTruth(const HeightfieldTruth&) = delete;
  HeightfieldTruth& operator=(const HeightfieldTruth&) = delete;

  // First hit along origin + t direction, t in [t_min, t_max].
  TruthHit intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                     double t_max) const override;
  // Is anything hit along origin + t direction, t in [t_min, t_max]? (shadow rays)
  bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                double t_max) const override;

  int subdivision() const override { return subdivision_; }
  // Largest deviation of the tessellation from the bilinear surface, in depth units.
  double tessellation_bound() const override { return bound_; }
  double build_ms() const override { return build_ms_; }
  float max_depth() const override { return max_depth_; }
  RTCScene scene() const { return scene_; }  // one tile, for benchmarks against raw Embree

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  int subdivision_ = 1;
  double bound_ = 0;
  double build_ms_ = 0;
  float max_depth_ = 1;
  glm::dvec2 offset_{0};  // tile origin: half a texel, so tile edges run through texel centres
};

}  // namespace rl
