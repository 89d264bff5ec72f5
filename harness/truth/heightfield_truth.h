#pragma once
// Embree ground truth of a heightfield relief: the bilinearly reconstructed surface of the
// map (what GL_LINEAR sampling defines), found exactly. Two stages per ray:
//
// 1. Embree finds where the surface can first be hit. It traces a tessellation of the surface
//    on every texel-centre crease (k x k sub-squares per bilinear cell) whose vertices are
//    lifted above the surface by a conservative bound: the tessellation's own deviation
//    (|C| / (4 k^2) for a cell of twist C) plus float rounding of its vertices. The lifted
//    surface lies above the bilinear one everywhere, so the ray cannot meet the bilinear
//    surface before it enters the lifted solid.
// 2. From there the texel cells under the ray are walked (2D DDA) and the ray is solved against
//    each bilinear patch exactly: the ray's depth minus the patch's is a quadratic in t, solved
//    in double (relief/heightfield_reference.h's bilinear_patch_hit). Where the ray climbs back
//    out of the band in which the lifted and the exact surface differ, Embree takes over again.
//
// So hit/miss and positions are exact to double rounding at every elevation and map size:
// the tessellation, capped by `max_vertices` at large maps, only decides how long stage 2
// walks (how thick the band is), never the answer. tessellation_bound() is 0.
//
// Space: (u, v, depth), depth growing downward, exactly the shaders' texture space. One tile
// is built; rays walk the tiles they cross (2D DDA over tile cells), so tiling and grazing
// rays cost no memory.
#include <atomic>
#include <vector>

#include <embree3/rtcore.h>

#include "core/sharded_counter.h"
#include "relief/relief_map.h"
#include "truth/truth_surface.h"

namespace rl {

// Largest |C| = |d00 - d10 - d01 + d11| over the map's bilinear cells: the twist that makes a
// bilinear patch non-planar (a k x k tessellation of a cell deviates by |C| / (4 k^2)).
double max_twist(const ReliefMap& map);

class HeightfieldTruth final : public TruthSurface {
 public:
  // `band_tolerance` (depth units): the lifted tessellation's target deviation from the
  // surface, which sets how finely it is tessellated -- a speed knob (a thinner band means
  // shorter exact walks), not an accuracy one. `max_vertices` caps its memory.
  HeightfieldTruth(const ReliefMap& map, double band_tolerance = 2e-3,
                   size_t max_vertices = 1u << 24, int forced_subdivision = 0);
  ~HeightfieldTruth();
  HeightfieldTruth(const HeightfieldTruth&) = delete;
  HeightfieldTruth& operator=(const HeightfieldTruth&) = delete;

  // First hit along origin + t direction, t in [t_min, t_max].
  TruthHit intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                     double t_max) const override;
  // Is anything hit along origin + t direction, t in [t_min, t_max]? (shadow rays)
  bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                double t_max) const override;
  // The first t in [t_min, t_max] at which the ray is at or below the surface, or NaN.
  double first_hit(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                   double t_max) const;

  int subdivision() const override { return subdivision_; }
  double tessellation_bound() const override { return 0.0; }  // exact (see above)
  double rounding_bound() const override { return kDoubleRounding; }
  // The widest band (depth units) between the lifted tessellation and the surface.
  double band() const { return band_max_; }
  double build_ms() const override { return build_ms_; }
  float max_depth() const override { return max_depth_; }
  RTCScene scene() const { return scene_; }  // one tile (lifted), for benchmarks

  // Work done so far: Embree queries of the lifted tessellation and texel cells solved exactly.
  uint64_t embree_queries() const { return embree_queries_.load(); }
  uint64_t exact_cells() const { return exact_cells_.load(); }

 private:
  // Stage 1: the first t in [t0, t1] at which the ray enters the lifted solid, or NaN.
  double lifted_entry(const glm::dvec3& origin, const glm::dvec3& direction, double t0,
                      double t1) const;
  // Stage 2 from t0: the exact hit (returned), or NaN with `resume` set to where the ray has
  // left the band above the surface (t_max when it reached the end of the ray).
  double exact_walk(const glm::dvec3& origin, const glm::dvec3& direction, double t0, double t_max,
                    double& resume) const;
  // Is (u, v, depth) provably above the lifted tessellation (outside the band)?
  bool above_band(const glm::dvec3& p) const;
  double depth_at(long i, long j) const;  // texel (i, j), wrapped like GL_REPEAT
  // Construction: each cell's band (band_, band_max_) at subdivision_, returning each cell's
  // lift; then the lifted tessellation in Embree (device_, scene_).
  std::vector<float> bound_bands();
  void build_lifted_grid(const std::vector<float>& lift);

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  int width_ = 0, height_ = 0;
  std::vector<float> depth_;  // the map's depths, row-major
  std::vector<float> band_;   // per texel cell (i, j) = texel centres i..i+1, j..j+1
  int subdivision_ = 1;
  double band_max_ = 0;
  double build_ms_ = 0;
  float max_depth_ = 1;
  glm::dvec2 offset_{0};  // tile origin: half a texel, so tile edges run through texel centres
  mutable ShardedCounter embree_queries_, exact_cells_;
};

}  // namespace rl
