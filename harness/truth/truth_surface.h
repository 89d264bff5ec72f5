#pragma once
// What the truth traces, in texture space (u, v, depth): the bilinear heightfield the map
// stands for (HeightfieldTruth), or the mesh it was baked from (MeshTruth) -- the "sampled"
// and "source" truth levels of DESIGN.md, so a table can split search error from
// representation error.
#include <atomic>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>
#include "core/sharded_counter.h"

namespace rl {

struct TruthHit {
  bool hit = false;
  double t = 0;      // ray parameter (same units as the direction given)
  glm::dvec3 point;  // (u, v, depth) of the hit, u and v not wrapped
  bool has_normal = false;
  glm::dvec3 normal{0, 0, -1};  // surface normal in the base's affine (u, v, depth) space, if known
  // The normal is instead a tangent-frame shading normal (x along u, y along v, z out of the
  // base), as a map stores it: a truth of the stored layers shades like the technique does.
  bool tangent_normal = false;
  bool has_albedo = false;  // the surface's own colour (a pattern's threads, a layer's colour)
  glm::dvec3 albedo{0};
};

class TruthSurface {
 public:
  virtual ~TruthSurface() = default;
  // First hit along origin + t direction, t in [t_min, t_max].
  virtual TruthHit intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                             double t_max) const = 0;
  // Is anything hit along origin + t direction, t in [t_min, t_max]? (shadow rays)
  virtual bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                        double t_max) const = 0;
  virtual float max_depth() const = 0;
  // Largest deviation from the surface it stands for, in depth units.
  virtual double tessellation_bound() const = 0;
  // How far (depth units, along the base's normal) a hit it reports may lie from the surface it
  // stands for: a ray crossing s depth units per unit of length meets a surface moved this far
  // 1 / s further along. The tessellation bound unless a truth says otherwise (one whose found
  // hits are exact while its tessellation_bound() states something else).
  virtual double vertical_bound() const { return tessellation_bound(); }
  // Rounding of its arithmetic, relative to the coordinates' magnitude (texture space, order
  // one): float for Embree's (kEmbreeRounding), double for truths solved on the CPU.
  virtual double rounding_bound() const { return kEmbreeRounding; }
  static constexpr double kEmbreeRounding = 1e-6;  // eight float ulps at magnitude one
  static constexpr double kDoubleRounding = 1e-12;
  virtual int subdivision() const { return 1; }
  virtual double build_ms() const = 0;
  uint64_t primary_rays() const { return primary_rays_.load(); }
  uint64_t shadow_rays() const { return shadow_rays_.load(); }

 protected:
  // The hit at ray parameter t, or none where t is NaN: the answer of a truth that solves for
  // the first crossing's parameter alone (no normal or albedo of its own).
  static TruthHit hit_at(const glm::dvec3& origin, const glm::dvec3& direction, double t) {
    TruthHit hit;
    if (std::isnan(t)) return hit;
    hit.hit = true;
    hit.t = t;
    hit.point = origin + direction * t;
    return hit;
  }
  mutable ShardedCounter primary_rays_;
  mutable ShardedCounter shadow_rays_;
};

}  // namespace rl
